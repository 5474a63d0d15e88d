"""Properties of Geometric Fairing: the operator's, the panel's (scene), the last run's (window manager), preferences.

The panel's tolerance, iterations, levels and time limit follow the add-on
preferences until they are changed in the panel; the operator takes every option
it is not given from the panel. So the preferences are the defaults of both.

The options are ``geofair.fair``'s, by its names and values: an enum's
identifiers are the library's strings ("uniform", "conformal", ...), and its
defaults come from ``geofair.defaults()``. The one value a Blender property
cannot hold as it is: the automatic time limit, None in the library (which
takes 0 as automatic too), 0 in the Time Limit property (:func:`property_value`,
:func:`option_values`).
"""

from collections.abc import Callable
from dataclasses import dataclass

import bpy
from bpy.props import BoolProperty, EnumProperty, FloatProperty, IntProperty, PointerProperty, StringProperty

from . import native
from .live import FRAME_PREPARE_FACTOR, FRAME_SECONDS_MIN

INNER_FAIRNESS_ITEMS = (
    (
        "uniform",
        "Uniform",
        "Regular vertex distribution: every vertex at the average of its neighbours along the mesh's "
        "edges (not across the diagonals that split quads and n-gons), in the tangent plane (uniform Laplacian)",
    ),
    (
        "conformal",
        "Conformal",
        "Texture-preserving: keeps the faired mesh discrete-conformal to the "
        "original (cotangent weights of the original mesh), so UV/texture distortion stays low",
    ),
    (
        "conformal_intrinsic",
        "Conformal (intrinsic Delaunay)",
        "Texture-preserving like Conformal, with the cotangent weights of the original mesh's intrinsic Delaunay "
        "triangulation: never negative, so vertices land where the conformal map puts them also on meshes of obtuse "
        "triangles (the same as Conformal where no triangle needs it). On rough meshes it can stall where Conformal "
        "converges",
    ),
)

OUTER_FAIRNESS_ITEMS = (
    (
        "intrinsic",
        "Intrinsic",
        "Intrinsic fairing, Δ_B H = 0: reproduces spheres, cylinders and minimal surfaces, independent of the mesh",
    ),
    (
        "bilaplacian",
        "Linear bilaplacian",
        "Linear Δ²f = 0 fairing, for comparison: fast but depends on the mesh and flattens curved regions",
    ),
)

BOUNDARY_ITEMS = (
    (
        "g1",
        "Tangent (G1)",
        "Keeps the positions of the region's boundary and the tangent planes of the surface around it (estimated "
        "from the unselected faces): the faired surface continues the surrounding surface smoothly",
    ),
    (
        "g0",
        "Position (G0)",
        "Keeps the positions of the region's boundary only: the minimal surface spanned by the boundary (mean "
        "curvature 0; a plane for a planar loop), the intrinsic counterpart of Blender's Fair Positions. Reads "
        "nothing from the faces around, so the region may reach the open mesh border; the surface may meet the "
        "surrounding one at a crease",
    ),
)

ITERATION_ITEMS = (
    (
        "auto",
        "Auto",
        "Newton's method, falling back to the paper's iteration where it stalls (Newton's method is tried "
        "again from the paper's iterate)",
    ),
    (
        "newton",
        "Newton",
        "Newton's method on all free vertices at once, level by level on the progressive mesh: few steps, "
        "but the memory of its sparse LU factors grows faster than the region",
    ),
    (
        "paper",
        "Paper",
        "The paper's local/global iteration with progressive-mesh multigrid (Levels): little memory, many iterations",
    ),
)

REMESH_ITEMS = (
    (
        "off",
        "Off",
        "Keep the triangles: only vertex positions change, UV maps and every other layer stay exactly as they were",
    ),
    (
        "if_needed",
        "If Needed",
        "Keep the triangles if the solve converges without new folds; otherwise replace the region's triangles by "
        "an even remesh and solve again. Changes the triangles then: UVs, colours and vertex groups are "
        "interpolated onto the new ones",
    ),
    (
        "always",
        "Always",
        "Replace the region's triangles by an even (isotropic) remesh at the boundary's edge length before fairing. "
        "Changes the triangles: UVs, colours and vertex groups are interpolated onto the new ones",
    ),
)
# The value geofair.fair takes for each Remesh item.
REMESH_VALUES = {"off": False, "if_needed": "if_needed", "always": True}

# The library's defaults (geofair.defaults()), by its names and values. Without the compiled
# module nothing can be faired and the panel shows why; the properties then start at their first
# item or lower bound.
_LIBRARY = native.geofair.defaults() if native.geofair is not None else {}
# fill_holes' own limit of iterations per fill (at most the caller's max_iterations).
_FILL_MAX_ITERATIONS = _LIBRARY.get("tuning", {}).get("schedule.fill_max_iterations", 2000)
DEFAULTS = {
    "inner_fairness": _LIBRARY.get("inner_fairness", INNER_FAIRNESS_ITEMS[0][0]),
    "outer_fairness": _LIBRARY.get("outer_fairness", OUTER_FAIRNESS_ITEMS[0][0]),
    "boundary": _LIBRARY.get("boundary", BOUNDARY_ITEMS[0][0]),
    "tolerance": _LIBRARY.get("tolerance", 1e-15),
    "max_iterations": _LIBRARY.get("max_iterations", 1),
    "levels": _LIBRARY.get("levels", 0),
    "iteration": _LIBRARY.get("iteration", ITERATION_ITEMS[0][0]),
    "time_limit": _LIBRARY.get("time_limit"),  # None: automatic
}
# The options the add-on passes to geofair.fair, under the same names; then the add-on's own.
LIBRARY_OPTION_NAMES = (
    "inner_fairness",
    "outer_fairness",
    "boundary",
    "tolerance",
    "max_iterations",
    "levels",
    "iteration",
    "time_limit",
)
OPTION_NAMES = (*LIBRARY_OPTION_NAMES, "remesh", "region_group", "pin_group", "use_hidden")
# Live Fair Drag's options taken from the panel when not given: Fair's but Remesh (a live region keeps its
# triangles); it adds Keep Details (LiveFairing's details), the offset and the frames.
LIVE_OPTION_NAMES = (*LIBRARY_OPTION_NAMES, "region_group", "pin_group", "use_hidden")
# geofair.fair's options that no property holds: scripts pass them (fair_object, fill_holes); the
# operators and the panel leave them at the library's defaults.
SCRIPT_OPTION_NAMES = ("normal_weighting", "damping", "cg_iterations", "tuning")
# geofair.fair's arguments that fair_object takes per element of the object, not as options.
MESH_ARGUMENT_NAMES = ("boundary_normals", "polygon_ids", "progress")


def property_value(name, value):
    """The value of option ``name`` as its Blender property holds it: the library's, but 0 for
    time_limit=None (automatic, as 0 is for the library), which a FloatProperty cannot hold."""
    return 0.0 if name == "time_limit" and value is None else value


def option_values(owner, names=OPTION_NAMES):
    """The options ``names`` of ``owner`` (the panel's settings, the operator) by the library's
    values, as :class:`fairing.FairingOptions` holds them: the properties' values, but a time
    limit of 0 is None (automatic)."""
    options = {name: getattr(owner, name) for name in names}
    options["time_limit"] = options["time_limit"] or None
    return options


def _inner_fairness(**options):
    return EnumProperty(
        name="Inner Fairness",
        description="Where the vertices sit on the faired surface",
        items=INNER_FAIRNESS_ITEMS,
        default=DEFAULTS["inner_fairness"],
        **options,
    )


def _outer_fairness(**options):
    return EnumProperty(
        name="Outer Fairness",
        description="Which surface is computed",
        items=OUTER_FAIRNESS_ITEMS,
        default=DEFAULTS["outer_fairness"],
        **options,
    )


def _boundary(**options):
    return EnumProperty(
        name="Boundary",
        description="What the faired surface keeps at the boundary of the region",
        items=BOUNDARY_ITEMS,
        default=DEFAULTS["boundary"],
        **options,
    )


def _tolerance(**options):
    return FloatProperty(
        name="Tolerance",
        description="Stop when the normalized residual of Δ_B H = 0 falls below this (dimensionless)",
        default=DEFAULTS["tolerance"],
        min=1e-15,
        max=1.0,
        precision=6,
        **options,
    )


def _max_iterations(**options):
    return IntProperty(
        name="Max Iterations",
        description=(
            "Upper bound on the number of fairing iterations on each level (for Fill Holes at most "
            f"{_FILL_MAX_ITERATIONS}, so that a fill that does not converge gives way to the next)"
        ),
        default=DEFAULTS["max_iterations"],
        min=1,
        soft_max=100000,
        **options,
    )


def _levels(**options):
    return IntProperty(
        name="Levels",
        description="Levels of the progressive-mesh multigrid: 0 picks the number from the region size and the "
        "solver, 1 solves the region as one mesh",
        default=DEFAULTS["levels"],
        min=0,
        max=12,
        **options,
    )


def _iteration(**options):
    return EnumProperty(
        name="Solver",
        description="How the fairing equations are solved (advanced; every choice solves the same equations)",
        items=ITERATION_ITEMS,
        default=DEFAULTS["iteration"],
        **options,
    )


def _automatic_time_limit(tuning):
    """The automatic time limit in words, from the library's tuning (``geofair.defaults()["tuning"]``)."""
    try:
        base, per_vertex, factor = (
            tuning[f"schedule.time_limit_{name}"] for name in ("base", "per_free_vertex", "hard_factor")
        )
    except KeyError:
        return "see geofair.fair"
    return (
        f"the residual not halved in {base:g} s plus {per_vertex * 1e3:g} ms per free vertex, the whole solve at "
        f"most {factor:g} times that"
    )


def _time_limit(**options):
    return FloatProperty(
        name="Time Limit",
        description="Seconds the solve may take; once spent, Fair stops and reports the run as not converged, "
        "Fill Holes gives the holes not yet filled the linear fill, and Live Fair Drag keeps the last good frame. "
        "0: automatic (as geofair.fair's time_limit None or 0): with the Auto solver a limit on time without "
        f"progress ({_automatic_time_limit(_LIBRARY.get('tuning', {}))}); Newton and Paper run to Max Iterations; "
        f"Live Fair Drag: each frame {FRAME_PREPARE_FACTOR:g} times the region's preparation, at least "
        f"{FRAME_SECONDS_MIN:g} s",
        default=property_value("time_limit", DEFAULTS["time_limit"]),
        min=0.0,
        soft_max=600.0,
        step=100,
        precision=1,
        **options,
    )


def _remesh(**options):
    return EnumProperty(
        name="Remesh",
        description="Whether the region's triangles may be replaced (opt-in: Off keeps every layer as it was)",
        items=REMESH_ITEMS,
        default="off",
        **options,
    )


def _region_group(**options):
    return StringProperty(
        name="Region Group",
        description="Vertex group that defines the region instead of the selection: the faces all of whose "
        "vertices have a non-zero weight in it. Empty: the selected faces",
        **options,
    )


def _pin_group(**options):
    return StringProperty(
        name="Pin Group",
        description="Vertex group of vertices inside the region that must not move (non-zero weight): they join "
        "the boundary (Tangent (G1): with their current normal). Empty: no pins",
        **options,
    )


def _use_hidden(**options):
    return BoolProperty(
        name="Use Hidden Faces",
        description="Let hidden faces take part like visible ones. Off: a hidden face is left out, as if the mesh "
        "ended there; its vertices never move, and those next to the region are fixed (Tangent (G1): with normals "
        "from the visible faces)",
        default=False,
        **options,
    )


def _keep_unconverged(**options):
    return BoolProperty(
        name="Keep Unconverged Result",
        description="Write the result into the mesh even when the solver stops before the residual reaches the "
        "tolerance (at Max Iterations, or where it stalls), with a warning. Off: an unconverged run leaves the mesh "
        "as it was and reports an error",
        default=False,
        **options,
    )


def _live_details(**options):
    return BoolProperty(
        name="Keep Details",
        description="Live Fair Drag keeps the region's details (its offsets from its own faired base) and moves them "
        "with the surface. Off: the region becomes the fair surface through the handle",
        default=False,
        **options,
    )


def _live_radius(**options):
    return FloatProperty(
        name="Radius",
        description="Live Fair Drag's region: the faces within this distance (the object's own units, before its "
        "scale) of the handle along the surface, the "
        "handle being the selected vertices (Proportional Editing's way; the mouse wheel or Page Up/Down changes it "
        "during the drag). 0: Fair's region (the selected faces or the Region vertex group) and the Pin group's handle",
        default=0.0,
        min=0.0,
        soft_max=10.0,
        subtype="DISTANCE",
        **options,
    )


def addon_preferences(context=None):
    """The add-on's :class:`FairingPreferences`, or None when it was not enabled through the preferences."""
    context = context or bpy.context
    addon = context.preferences.addons.get(__package__)
    return addon.preferences if addon is not None else None


def preference(name, context=None):
    """The preferred default of option ``name`` (tolerance, max_iterations, levels, time_limit), as its
    property holds it."""
    preferences = addon_preferences(context)
    return getattr(preferences, name) if preferences is not None else property_value(name, DEFAULTS[name])


def _follows_preference(name):
    """Getter and setter of a panel option that reads the preference until it is set in the panel."""
    key = "_" + name

    def get(self):
        return self.get(key, preference(name))

    def set(self, value):
        self[key] = value

    return {"get": get, "set": set}


class FairingPreferences(bpy.types.AddonPreferences):
    """Defaults of the fairing options, for the panel and the operator."""

    bl_idname = __package__

    tolerance: _tolerance()
    max_iterations: _max_iterations()
    levels: _levels()
    time_limit: _time_limit()

    def draw(self, context):
        layout = self.layout
        layout.use_property_split = True
        layout.label(text="Defaults of the Fairing panel and of the operator:")
        for name in ("tolerance", "max_iterations", "levels", "time_limit"):
            layout.prop(self, name)


# The options that panels and redo panels keep in a closed Advanced sub-panel: the solver's
# stopping rules and its method, which the defaults suit.
ADVANCED_OPTION_NAMES = ("tolerance", "max_iterations", "levels", "iteration", "time_limit")
# Their labels where the property's name is too long for the sidebar (the redo panels use them too).
ADVANCED_LABELS = {"max_iterations": "Iterations"}


def draw_advanced_options(layout, data):
    """One row per ADVANCED_OPTION_NAMES of ``data`` (the scene's settings or an operator's
    properties), labelled by ADVANCED_LABELS where one is given."""
    for name in ADVANCED_OPTION_NAMES:
        if name in ADVANCED_LABELS:
            layout.prop(data, name, text=ADVANCED_LABELS[name])
        else:
            layout.prop(data, name)


class SolverProperties:
    """Mixin with the library's options (LIBRARY_OPTION_NAMES) of the solving operators, and their redo panel.

    SKIP_SAVE: an option that is not given comes from the panel's settings
    (which follow the preferences), never from the previous call.
    """

    inner_fairness: _inner_fairness(options={"SKIP_SAVE"})
    outer_fairness: _outer_fairness(options={"SKIP_SAVE"})
    boundary: _boundary(options={"SKIP_SAVE"})
    tolerance: _tolerance(options={"SKIP_SAVE"})
    max_iterations: _max_iterations(options={"SKIP_SAVE"})
    levels: _levels(options={"SKIP_SAVE"})
    iteration: _iteration(options={"SKIP_SAVE"})
    time_limit: _time_limit(options={"SKIP_SAVE"})

    def inherit_panel(self, settings, names):
        """Set each option of ``names`` that the operator was not given from the panel's ``settings``."""
        for name in names:
            if not self.properties.is_property_set(name):
                setattr(self, name, getattr(settings, name))

    def draw(self, context):
        """The redo panel: the operator's properties in order, ADVANCED_OPTION_NAMES in a closed Advanced
        sub-panel (``UILayout.panel``, Blender 4.1+; before, under an Advanced heading)."""
        layout = self.layout
        layout.use_property_split = True
        layout.use_property_decorate = False
        props = self.properties
        names = [p.identifier for p in props.bl_rna.properties if p.identifier != "rna_type" and not p.is_hidden]
        for name in names:
            if name not in ADVANCED_OPTION_NAMES:
                layout.prop(props, name)
        if hasattr(layout, "panel"):
            header, body = layout.panel("geometric_fairing_advanced", default_closed=True)
            header.label(text="Advanced")
        else:
            body = layout.column(heading="Advanced")
        if body is not None:  # None: the sub-panel is closed
            draw_advanced_options(body, props)


class FairingProperties(SolverProperties):
    """Mixin with the Fair operator's options, shown in the redo panel: the library's
    (SolverProperties) and the region's. ``keep_unconverged`` is the operator's alone (off
    unless given or ticked in the redo panel).
    """

    remesh: _remesh(options={"SKIP_SAVE"})
    region_group: _region_group(options={"SKIP_SAVE"})
    pin_group: _pin_group(options={"SKIP_SAVE"})
    use_hidden: _use_hidden(options={"SKIP_SAVE"})
    keep_unconverged: _keep_unconverged(options={"SKIP_SAVE"})


class FairingSettings(bpy.types.PropertyGroup):
    """The Fairing panel's options, ``scene.geometric_fairing``."""

    inner_fairness: _inner_fairness()
    outer_fairness: _outer_fairness()
    boundary: _boundary()
    tolerance: _tolerance(**_follows_preference("tolerance"))
    max_iterations: _max_iterations(**_follows_preference("max_iterations"))
    levels: _levels(**_follows_preference("levels"))
    iteration: _iteration()
    time_limit: _time_limit(**_follows_preference("time_limit"))
    remesh: _remesh()
    region_group: _region_group()
    pin_group: _pin_group()
    use_hidden: _use_hidden()
    live_details: _live_details()
    live_radius: _live_radius()


@dataclass(frozen=True)
class RunFigure:
    """One figure of a run, in one place: the attribute of ``fairing.FairingReport`` of that name,
    the property of :class:`FairingLastRun` that keeps it for the panel, and the panel's row.

    Attributes:
        name: the attribute and property name.
        label: the panel's row label (the property's name).
        kind: int, float or str: the property's type.
        description: the property's tooltip.
        combine: the figure of several objects' runs from theirs (an iterable of values).
        text: the panel's text of a value.
        shown: whether the panel shows a value (e.g. only non-zero counts).
    """

    name: str
    label: str
    kind: type
    description: str
    combine: Callable
    text: Callable = str
    shown: Callable = lambda value: True


def _solvers(values):
    return ", ".join(sorted({value for value in values if value}))


# fmt: off
RUN_FIGURES = (
    RunFigure("free_vertices", "Free vertices", int, "Vertices that could move", sum),
    RunFigure("pinned_vertices", "Pinned vertices", int, "Vertices of the region kept fixed by the pin group", sum,
              shown=bool),
    RunFigure("iterations", "Iterations", int, "Fairing iterations (all levels), or Newton steps", sum),
    RunFigure("residual", "Residual", float, "The last normalized residual of Δ_B H = 0 (dimensionless); "
              "the largest of several objects", max, "{:.2g}".format),
    RunFigure("seconds", "Time", float, "Wall time of the solves, seconds", sum, "{:.2f} s".format),
    RunFigure("folds", "Folded edges", int, "Edges of the free region whose two triangles face apart after the run "
              "(triangles flipped over)", sum, shown=bool),
    RunFigure("triangles_added", "New triangles", int, "Triangles the remesh or the fill created (the old region's "
              "faces replaced, or the holes filled)", sum, shown=bool),
    RunFigure("iteration", "Solver", str, "The solver that produced the result: newton or paper (empty: none)",
              _solvers, str.title, bool),
)
# fmt: on

_PROPERTY_TYPES = {int: IntProperty, float: FloatProperty, str: StringProperty}


class FairingLastRun(bpy.types.PropertyGroup):
    """Figures of the last run, shown in the panel (on the window manager: not undone, not per scene);
    those of a run's report are added from :data:`RUN_FIGURES` below."""

    status: EnumProperty(
        items=(
            ("NONE", "None", "No run yet"),
            ("CONVERGED", "Converged", "The residual fell below the tolerance"),
            (
                "NOT_CONVERGED",
                "Not converged",
                "Stopped before the tolerance; the mesh was changed only with Keep Unconverged Result",
            ),
            ("CANCELLED", "Cancelled", "Cancelled; the mesh was left as it was"),
            ("ERROR", "Error", "Failed; the mesh was left as it was"),
        ),
        default="NONE",
    )
    message: StringProperty()
    object_name: StringProperty(description="The object faired, or the objects (comma-separated)")
    not_faired: StringProperty(description="Objects in Edit Mode that could not be faired, with the reason")
    inner_fairness: StringProperty()
    outer_fairness: StringProperty()
    boundary: StringProperty()
    tolerance: FloatProperty()
    has_uv: BoolProperty()
    uv_triangles: IntProperty()
    uv_before_mean: FloatProperty()
    uv_before_max: FloatProperty()
    uv_after_mean: FloatProperty()
    uv_after_max: FloatProperty()


for _figure in RUN_FIGURES:
    FairingLastRun.__annotations__[_figure.name] = _PROPERTY_TYPES[_figure.kind](
        name=_figure.label, description=_figure.description
    )


class FairingSession(bpy.types.PropertyGroup):
    """``window_manager.geometric_fairing``: the last run and the mean-curvature colour range."""

    last_run: PointerProperty(type=FairingLastRun)
    curvature_limit: FloatProperty(
        name="Curvature Range",
        description="Mean curvature mapped to full red (+) and blue (-), in 1/length",
    )


CLASSES = (FairingPreferences, FairingSettings, FairingLastRun, FairingSession)


def register():
    """Register the property groups and attach them to the scene and the window manager."""
    for cls in CLASSES:
        bpy.utils.register_class(cls)
    bpy.types.Scene.geometric_fairing = PointerProperty(type=FairingSettings)
    bpy.types.WindowManager.geometric_fairing = PointerProperty(type=FairingSession)


def unregister():
    """Detach and unregister the property groups."""
    del bpy.types.WindowManager.geometric_fairing
    del bpy.types.Scene.geometric_fairing
    for cls in reversed(CLASSES):
        bpy.utils.unregister_class(cls)
