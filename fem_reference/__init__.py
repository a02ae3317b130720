"""Finite-element penalty-contact reference (scikit-fem on gmsh meshes).

Shares nothing with ``halfspace`` but the case model and the result container.
"""
