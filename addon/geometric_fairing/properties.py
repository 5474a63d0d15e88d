"""Operator properties of Geometric Fairing, shown in the redo panel."""

from bpy.props import EnumProperty, FloatProperty, IntProperty

INNER_FAIRNESS_ITEMS = (
    (
        "UNIFORM",
        "Uniform",
        "Regular vertex distribution: every vertex at the average of its neighbours "
        "in the tangent plane (uniform Laplacian)",
    ),
    (
        "CONFORMAL",
        "Conformal",
        "Texture-preserving: keeps the faired mesh discrete-conformal to the "
        "original (cotangent weights of the original mesh), so UV/texture distortion stays low",
    ),
)

OUTER_FAIRNESS_ITEMS = (
    (
        "INTRINSIC",
        "Intrinsic",
        "Intrinsic fairing, Δ_B H = 0: reproduces spheres, cylinders and minimal surfaces, independent of the mesh",
    ),
    (
        "BILAPLACIAN",
        "Linear bilaplacian",
        "Linear Δ²f = 0 fairing, for comparison: fast but depends on the mesh and flattens curved regions",
    ),
)


class FairingProperties:
    """Mixin with the fairing parameters; the operator inherits its annotations."""

    inner_fairness: EnumProperty(
        name="Inner Fairness",
        description="Where the vertices sit on the faired surface",
        items=INNER_FAIRNESS_ITEMS,
        default="UNIFORM",
    )
    outer_fairness: EnumProperty(
        name="Outer Fairness",
        description="Which surface is computed",
        items=OUTER_FAIRNESS_ITEMS,
        default="INTRINSIC",
    )
    tolerance: FloatProperty(
        name="Tolerance",
        description="Stop when the normalized residual of Δ_B H = 0 falls below this (dimensionless)",
        default=1e-4,
        min=1e-12,
        max=1.0,
        precision=6,
    )
    max_iterations: IntProperty(
        name="Max Iterations",
        description="Upper bound on the number of fairing iterations",
        default=20000,
        min=1,
        soft_max=100000,
    )
