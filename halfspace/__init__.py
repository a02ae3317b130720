"""Influence-coefficient (boundary-element) solver on the elastic half-space.

Implements shared/paper/formulation.md: kernels (Eq. 5, 41), FFT influence products,
orthotropic frictional contact (Eq. 7-17, section 3.4), orthotropic Archard wear
(Eq. 18-23) and subsurface stresses (Eq. 32-34, Appendices A and C).
"""
