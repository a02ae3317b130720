"""The Kratos model of one frictionless sphere-on-plane contact: the two quarter bodies
of :mod:`kratos_adapter.mesh` (trilinear hexahedra; linear tetrahedra would do too),
small-displacement elements with Kratos' linear elastic law, mortar
augmented-Lagrangian frictionless contact (``ALMContactFrictionless``, Kratos'
``ALMContactProcess`` with its automatic penalty and scale factor), driven by the
approach δ of the sphere's far face (the plane's far face held) in Kratos' static
contact solver, one thread, AMGCL (:data:`LINEAR_SOLVER`).

The slave face is the sphere's (body a): with the plane's face as slave, the multiplier
at the nodes on the symmetry planes near the centre came out up to 1.9 p0 (Hertz: 1.0)
on the bundled Hertz case at h = a0/6 (tetrahedra), whatever the mesh ratio.

Kratos is driven step by step (:class:`Model`): each :meth:`Model.solve` is one load step
at a new δ from the last converged state (the boundary values set on the nodes, not by
a process with a time interval), so the secant search for the case's normal load
(:func:`kratos_adapter.run.load_search`) costs a few Newton iterations per step.

Reserved names avoided: a sub-model part named ``Contact`` is Kratos' own.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from reports.plugin import silenced

from .mesh import Body

#: the linear solver: AMGCL (Kratos' iterative solver) to a relative 1e-9: Eigen's sparse
#: LU (the wheel has no PARDISO) took 5.2 s per solve at 18 000 unknowns where AMGCL
#: took 0.36 s per Newton iteration, and AMGCL to 1e-6 gave a peak pressure of 2 p0
#: (benchmarks/README.md, "Kratos through the gates")
LINEAR_SOLVER = """{"solver_type": "amgcl", "tolerance": 1.0e-9, "max_iteration": 1000,
                    "krylov_type": "lgmres", "smoother_type": "ilu0", "verbosity": 0}"""
#: Kratos' settings (its ``ProjectParameters`` keys); tolerances of the Newton solve
SETTINGS = """{
    "problem_data": {"problem_name": "contact_vv", "parallel_type": "OpenMP",
                     "echo_level": 0, "start_time": 0.0, "end_time": 1.0e6},
    "solver_settings": {
        "solver_type": "Static", "model_part_name": "Structure", "domain_size": 3,
        "echo_level": 0, "analysis_type": "non_linear",
        "model_import_settings": {"input_type": "use_input_model_part"},
        "material_import_settings": {"materials_filename": ""},
        "time_stepping": {"time_step": 1.0},
        "convergence_criterion": "contact_residual_criterion",
        "displacement_relative_tolerance": 1.0e-6, "displacement_absolute_tolerance": 1.0e-12,
        "residual_relative_tolerance": 1.0e-6, "residual_absolute_tolerance": 1.0e-12,
        "max_iteration": 30,
        "contact_settings": {"mortar_type": "ALMContactFrictionless"},
        "linear_solver_settings": {}
    },
    "processes": {
        "contact_process_list": [{
            "python_module": "alm_contact_process",
            "kratos_module": "KratosMultiphysics.ContactStructuralMechanicsApplication",
            "process_name": "ALMContactProcess",
            "Parameters": {
                "model_part_name": "Structure",
                "contact_model_part": {"0": ["FaceA", "FaceB"]},
                "assume_master_slave": {"0": ["FaceA"]},
                "contact_type": "Frictionless"
            }
        }]
    },
    "output_processes": {}
}"""


def threads() -> None:
    """One thread for Kratos (its OpenMP loops) and its linear solver."""
    import KratosMultiphysics as KM

    KM.ParallelUtilities.SetNumThreads(1)


@dataclass(frozen=True)
class Material:
    E: float
    nu: float


class Model:
    """A Kratos analysis of the two bodies, advanced one load step per :meth:`solve`."""

    def __init__(self, a: Body, b: Body, mat_a: Material, mat_b: Material):
        with silenced():
            import KratosMultiphysics as KM
            import KratosMultiphysics.ContactStructuralMechanicsApplication  # noqa: F401
            import KratosMultiphysics.LinearSolversApplication  # noqa: F401
            import KratosMultiphysics.StructuralMechanicsApplication as SMA
            from KratosMultiphysics.StructuralMechanicsApplication.structural_mechanics_analysis import (  # noqa: E501
                StructuralMechanicsAnalysis,
            )

            threads()
            KM.Logger.GetDefaultOutput().SetSeverity(KM.Logger.Severity.WARNING)
            self.KM = KM
            self.model = KM.Model()
            params = KM.Parameters(SETTINGS)
            params["solver_settings"].RemoveValue("linear_solver_settings")
            params["solver_settings"].AddValue("linear_solver_settings",
                                               KM.Parameters(LINEAR_SOLVER))
            self.stage = StructuralMechanicsAnalysis(self.model, params)
            mp = self.model["Structure"]
            self.offset_a = b.nodes.shape[0]  # node ids: body b first, then body a
            self._build(mp, a, b, mat_a, mat_b, SMA)
            self.stage.Initialize()
        self.a, self.b = a, b
        self.mp = mp
        self.time = 0.0

    def _build(self, mp, a: Body, b: Body, mat_a: Material, mat_b: Material, SMA) -> None:
        KM = self.KM
        for pid, mat in ((1, mat_a), (2, mat_b)):
            prop = mp.GetProperties()[pid]
            prop.SetValue(KM.YOUNG_MODULUS, mat.E)
            prop.SetValue(KM.POISSON_RATIO, mat.nu)
            prop.SetValue(KM.DENSITY, 1.0)
            prop.SetValue(KM.CONSTITUTIVE_LAW, SMA.LinearElastic3DLaw())
        for body, offset, pid, part, face in ((b, 0, 2, "BodyB", "FaceB"),
                                             (a, self.offset_a, 1, "BodyA", "FaceA")):
            sub = mp.CreateSubModelPart(part)
            prop = mp.GetProperties()[pid]
            ids = np.arange(body.nodes.shape[0]) + offset + 1
            for i, (x, y, z) in zip(ids, body.nodes, strict=True):
                sub.CreateNewNode(int(i), float(x), float(y), float(z))
            first = mp.NumberOfElements() + 1
            element = f"SmallDisplacementElement3D{body.cells.shape[1]}N"
            condition = f"SurfaceCondition3D{body.contact.shape[1]}N"
            for k, t in enumerate(body.cells):
                sub.CreateNewElement(element, first + k,
                                     [int(n) for n in t + offset + 1], prop)
            faces = mp.CreateSubModelPart(face)
            faces.AddNodes([int(n) for n in np.unique(body.contact) + offset + 1])
            first = mp.NumberOfConditions() + 1
            for k, t in enumerate(body.contact):
                faces.CreateNewCondition(condition, first + k,
                                         [int(n) for n in t + offset + 1], prop)
        # symmetry planes, the plane's far face held; the sphere's far face is driven
        for body, offset in ((a, self.offset_a), (b, 0)):
            for face, var in (("x0", KM.DISPLACEMENT_X), ("y0", KM.DISPLACEMENT_Y)):
                for n in body.faces[face] + offset + 1:
                    mp.GetNode(int(n)).Fix(var)
        for n in b.faces["far"] + 1:
            mp.GetNode(int(n)).Fix(KM.DISPLACEMENT_Z)
        self.driven = [mp.GetNode(int(n)) for n in a.faces["far"] + self.offset_a + 1]

    def solve(self, approach: float) -> bool:
        """One load step to the approach δ = ``approach`` [mm] of the far faces; whether
        Kratos' Newton solve converged."""
        KM = self.KM
        stage = self.stage
        with silenced():
            stage.time = stage._AdvanceTime()
            for node in self.driven:
                node.Fix(KM.DISPLACEMENT_Z)
                node.SetSolutionStepValue(KM.DISPLACEMENT_Z, 0, -approach)
            stage.InitializeSolutionStep()
            converged = bool(stage.SolveSolutionStep())
            stage.FinalizeSolutionStep()
        return converged

    def load(self) -> float:
        """The normal load of the quarter [N]: the reaction of the plane's far face."""
        KM = self.KM
        return float(sum(self.mp.GetNode(int(n) + 1).GetSolutionStepValue(KM.REACTION_Z)
                         for n in self.b.faces["far"]))

    def pressure(self) -> np.ndarray:
        """The contact pressure [MPa] at the nodes of the slave face (the sphere's, body
        a; 0 at its other nodes): the augmented normal contact pressure of the active
        nodes (the multiplier times the scale factor plus the penalised gap, which the
        converged active set makes the multiplier's), compressive positive."""
        import KratosMultiphysics.ContactStructuralMechanicsApplication as CSMA

        p = np.zeros(self.a.nodes.shape[0])
        for n in np.unique(self.a.contact):
            node = self.mp.GetNode(int(n) + self.offset_a + 1)
            if node.Is(self.KM.ACTIVE):
                p[n] = -node.GetValue(CSMA.AUGMENTED_NORMAL_CONTACT_PRESSURE)
        return p

    def iterations(self) -> int:
        """The Newton iterations of the last load step."""
        return int(self.mp.ProcessInfo[self.KM.NL_ITERATION_NUMBER])

    def stresses(self, body: str) -> np.ndarray:
        """The Cauchy stress of each element of ``body`` ('a' or 'b') at its nodes,
        (m, nodes per element, 6) as (sxx, syy, szz, sxy, sxz, syz) [MPa]: the values at
        its 2 x 2 x 2 Gauss points extrapolated trilinearly to its corners (a hexahedron),
        the one value of a linear tetrahedron at each of its nodes."""
        KM = self.KM
        info = self.mp.ProcessInfo
        part = self.mp.GetSubModelPart("BodyA" if body == "a" else "BodyB")
        cells = (self.a if body == "a" else self.b).cells
        offset = self.offset_a if body == "a" else 0
        out = np.empty((cells.shape[0], cells.shape[1], 6))
        order = [0, 1, 2, 3, 5, 4]  # Kratos' Voigt order: xx yy zz xy yz xz
        for k, elem in enumerate(part.Elements):
            s = np.array([list(v) for v in
                          elem.CalculateOnIntegrationPoints(KM.CAUCHY_STRESS_VECTOR, info)])
            s = s[:, order]
            if s.shape[0] == 1:
                out[k] = s[0]
                continue
            gp = np.array([list(v) for v in
                           elem.CalculateOnIntegrationPoints(KM.INTEGRATION_COORDINATES, info)])
            ids = [n.Id - offset - 1 for n in elem.GetNodes()]
            out[k] = extrapolate(self.a.nodes if body == "a" else self.b.nodes, ids, gp, s)
        return out


def extrapolate(nodes: np.ndarray, ids: list[int], gp: np.ndarray, values: np.ndarray
                ) -> np.ndarray:
    """Values at a hexahedron's 2 x 2 x 2 Gauss points ``gp`` extrapolated trilinearly to
    its corners ``nodes[ids]``: in the element's axes (it is a box up to the sphere's
    map), a Gauss point sits at ±1/√3 and a corner at ±1, so a corner's weight on the
    point of signs s is Π (1 + √3 s·c) / 2."""
    corners = nodes[ids]
    centre = corners.mean(axis=0)
    c = np.sign(corners - centre)
    g = np.sign(gp - centre)
    w = np.prod((1.0 + np.sqrt(3.0) * c[:, None, :] * g[None, :, :]) / 2.0, axis=-1)
    return w @ values
