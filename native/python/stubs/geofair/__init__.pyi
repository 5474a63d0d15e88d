"""
Intrinsic mesh fairing: discrete solutions of Δ_B H = 0 with G1 boundary conditions
(Schneider & Kobbelt, Geometric fairing of irregular meshes for free-form surface
design, CAGD 18, 2001).
"""
from __future__ import annotations
import collections.abc
import numpy
import numpy.typing
import scipy.sparse
import typing
__all__: list[str] = ['FairingResult', 'FillResult', 'HoleFill', 'InvalidInputError', 'LiveFairing', 'RemeshedRegion', 'SolverError', 'boundary_loops', 'boundary_normals', 'cotangent_laplacian', 'defaults', 'fair', 'fill_holes', 'holes_to_fill', 'intrinsic_delaunay', 'intrinsic_delaunay_laplacian', 'mean_curvature', 'progressive_mesh', 'read_mesh', 'relax_inner_fairness', 'remesh_region', 'write_mesh']
class InvalidInputError(ValueError):
    pass
class SolverError(RuntimeError):
    pass
class FairingResult:
    """
    Result of geofair.fair.
    """
    def __repr__(self) -> str:
        ...
    @property
    def converged(self) -> bool:
        """
        True if the residual reached the tolerance.
        """
    @property
    def faces(self) -> typing.Annotated[numpy.typing.NDArray[numpy.int32], "[m, 3]"]:
        """
        (m', 3) int32 triangles of the result: the input's unless .remeshed (then the input faces without a free vertex, unchanged and first, then the region's new ones; fill_holes: the input's faces, then the fill's).
        """
    @property
    def folds(self) -> int:
        """
        Edges with a free vertex whose two triangles face apart (normals with a negative dot product) in .vertices: triangles the result flips over. A converged result can have them where the G1 data turn faster than the mesh resolves, or keep them from a folded input; .message then says so.
        """
    @property
    def free(self) -> numpy.typing.NDArray[numpy.bool_]:
        """
        (n',) bool: the result's free vertices (the input's mask unless .remeshed; fill_holes: exactly the new vertices).
        """
    @property
    def iteration(self) -> str:
        """
        The iteration that produced the result: "newton" or "paper".
        """
    @property
    def iterations(self) -> int:
        """
        Number of iterations M_k -> M_{k+1} performed.
        """
    @property
    def iterations_per_level(self) -> list[int]:
        """
        Iterations on each level, coarsest first.
        """
    @property
    def message(self) -> str:
        """
        How the solve ended, one sentence: "converged (...)" or why not (the time limit, max_iterations, cancelled), with the residual and tolerance.
        """
    @property
    def new_folds(self) -> int:
        """
        Those of .folds whose two triangles did not face apart in the input.
        """
    @property
    def newton_iterations(self) -> int:
        """
        Newton steps performed, including an attempt that iteration="auto" abandoned for the paper's iteration.
        """
    @property
    def origin_barycentric(self) -> typing.Annotated[numpy.typing.NDArray[numpy.float64], "[m, 3]"]:
        """
        (n', 3) float64 barycentric coordinates in .origin_face (rows sum to 1); zero rows where .origin_face is -1. With .origin_face they carry per-corner data (UVs) over from the input.
        """
    @property
    def origin_face(self) -> numpy.typing.NDArray[numpy.int32]:
        """
        (n',) int32: for each free vertex of a remeshed region the input face (row of the input faces) it was created on, on the input surface before fairing; -1 for the other rows and for every row unless .remeshed.
        """
    @property
    def phase_seconds(self) -> list[tuple[str, float]]:
        """
        Wall-clock seconds of the solve's phases, a list of (name, seconds) in the order they ran: "remesh" where the region was remeshed, "hierarchy", then per level l (0 = coarsest) "level l initial mesh", "level l set-up" and, for Newton's method, "level l inner fairness", "level l Newton steps", "level l polishes", for the paper's iteration "level l iterations" (an abandoned attempt's phases included). They do not overlap: their sum stays below the call's wall time.
        """
    @property
    def remeshed(self) -> bool:
        """
        True when the region's triangles were replaced (fair's remesh).
        """
    @property
    def residual(self) -> float:
        """
        Normalized residual of the returned mesh (dimensionless, see fair).
        """
    @property
    def stop_reason(self) -> str:
        """
        Why the solve ended, message's first clause as a value: "converged"; "max_iterations" (a level spent max_iterations, or Newton's method stalled with iteration="newton"); "time_limit" (time_limit, or the automatic limit's hard cap); "no_progress" (the automatic limit: the residual did not halve for its span); "cancelled" (progress returned False); "diverged" (iteration="auto"'s last attempt failed: the input is returned).
        """
    @property
    def unreferenced(self) -> numpy.typing.NDArray[numpy.int32]:
        """
        (k,) int32: rows of .vertices in no face (input free rows that the remesh did not reuse, input positions kept); empty unless .remeshed.
        """
    @property
    def vertices(self) -> typing.Annotated[numpy.typing.NDArray[numpy.float64], "[m, 3]"]:
        """
        (n', 3) float64 positions; fixed rows are bit-identical to the input. n' = n unless .remeshed (then max(n, #fixed + #new free)).
        """
    @property
    def vertices_per_level(self) -> list[int]:
        """
        Region vertices (free and G1 boundary) on each level, coarsest first.
        """
class RemeshedRegion:
    """
    Result of geofair.remesh_region.
    """
    def __repr__(self) -> str:
        ...
    @property
    def faces(self) -> typing.Annotated[numpy.typing.NDArray[numpy.int32], "[m, 3]"]:
        """
        (m', 3) int32 triangles: the input faces without a free vertex (unchanged, in input order), then the region's new triangles.
        """
    @property
    def free(self) -> numpy.typing.NDArray[numpy.bool_]:
        """
        (n',) bool: True exactly at the new region's free vertices.
        """
    @property
    def origin_barycentric(self) -> typing.Annotated[numpy.typing.NDArray[numpy.float64], "[m, 3]"]:
        """
        (n', 3) float64 barycentric coordinates in origin_face (rows sum to 1; vertices[i] = Σ_k b[i, k] * input_vertices[input_faces[f, k]] to round-off); zeros where origin_face is -1.
        """
    @property
    def origin_face(self) -> numpy.typing.NDArray[numpy.int32]:
        """
        (n',) int32: for each free vertex the input face (row of the input faces) its position lies on; -1 for fixed vertices and unreferenced rows.
        """
    @property
    def target_edge_length(self) -> float:
        """
        float: the target edge length L the remesh used (the given one, or the mean length of the region's border edges, of all its edges where it has no border), mesh units.
        """
    @property
    def unreferenced(self) -> numpy.typing.NDArray[numpy.int32]:
        """
        (k,) int32: input free rows that no new vertex reuses (in no face, not free).
        """
    @property
    def vertices(self) -> typing.Annotated[numpy.typing.NDArray[numpy.float64], "[m, 3]"]:
        """
        (n', 3) float64 positions, mesh units; rows of fixed vertices are bit-identical to the input, n' = max(n, #fixed + #new free).
        """
class HoleFill:
    """
    What geofair.fill_holes did with one hole.
    """
    def __repr__(self) -> str:
        ...
    @property
    def attempts(self) -> list:
        """
        Every fill tried, in order: a list of dicts with "method", "converged", "folds", "seconds" (wall-clock) and "message" (the solve's, or why it was not made).
        """
    @property
    def converged(self) -> bool:
        """
        The kept fill's solve converged.
        """
    @property
    def filled(self) -> bool:
        """
        True unless the hole was left open.
        """
    @property
    def folds(self) -> int:
        """
        Folded edges of the kept fill: edges of its triangles, among them and with the input's triangles at the loop, whose two triangles' normals have a non-positive dot product.
        """
    @property
    def loop(self) -> numpy.typing.NDArray[numpy.int32]:
        """
        (k,) int32: the hole's loop, input vertex indices in the direction of the missing face (as geofair.boundary_loops orders them).
        """
    @property
    def method(self) -> str:
        """
        The fill kept: "intrinsic" (G1, Δ_B H = 0 at the loop's edge length), "intrinsic_finer" (at half of it), "intrinsic_trimmed" (after rim="trim" removed faces at the rim), "g0" (positions only at the loop: H = 0), "linear" (the linear Δ²f = 0 fill of the same patch), or "none": left open (.reason says why). With boundary="g0" the first fill is "g0", and "intrinsic_finer" and "intrinsic_trimmed" are G0 fills too.
        """
    @property
    def new_faces(self) -> int:
        """
        Triangles the fill added.
        """
    @property
    def new_vertices(self) -> int:
        """
        Vertices the fill added.
        """
    @property
    def reason(self) -> str:
        """
        Left open: why, one clause for a user; filled: "".
        """
    @property
    def removed_faces(self) -> numpy.typing.NDArray[numpy.int32]:
        """
        (r,) int32: input face indices (rows of the input faces) removed at this hole's rim, sorted; empty unless rim="trim" trimmed it.
        """
    @property
    def residual(self) -> float:
        """
        The kept fill's normalized residual (dimensionless, see geofair.fair).
        """
class FillResult(FairingResult):
    """
    Result of geofair.fill_holes: geofair.FairingResult's fields for the filled mesh, and a record per hole.
    """
    def __repr__(self) -> str:
        ...
    @property
    def holes(self) -> list[HoleFill]:
        """
        list of geofair.HoleFill: the holes in the order of the loops (given, or geofair.holes_to_fill's), then the loops the rule left open (method "none", with the reason).
        """
    @property
    def removed_faces(self) -> numpy.typing.NDArray[numpy.int32]:
        """
        (r,) int32: the input face indices removed at the rims (rim="trim"), sorted; the result's faces are the other input faces in their order, then the fills'.
        """
class LiveFairing:
    """
    A fairing region prepared once and faired again for new positions of its
    fixed vertices: live intrinsic modelling, a handle dragged through the surface (beyond the
    paper; Schneider & Kobbelt 2001, section 8, asks for it).
    
        live = geofair.LiveFairing(vertices, faces, free, **fair_options)
        result = live.update(new_vertices)  # a FairingResult, as geofair.fair's
    
    The constructor fairs the region cold (geofair.fair; live.result) and keeps what does not
    depend on the fixed vertices' positions: the region, its one-rings, the symbolic analysis
    of the Newton preconditioner, the inner fairness pattern. Each update starts from the last
    converged frame with the new fixed positions (a warm start): a tangential relaxation
    towards inner fairness and Newton's method on the region (eq. (12)), preconditioned by the
    last frame's factorizations where GMRES still converges on them, and fair's polish near the end. A
    frame whose warm start does not converge in max_warm_steps Newton steps runs the cold path,
    geofair.fair's whole schedule, and its .message says so.
    
    Fixed vertices inside the region (a handle: fixed vertices with free neighbours, surrounded
    by the region) are boundary conditions like the outer ones, as in geofair.fair: their
    positions and, with boundary="g1", their tangent planes, estimated from their own
    triangles (those without a free vertex) as geofair.boundary_normals does, again from the
    new positions at every update: a rigid handle turns its tangent planes with it. A handle
    needs such triangles (two rings of fixed vertices give the estimate its samples), or
    boundary_normals at each update.
    
    A frame's input is its positions of the fixed vertices with the free vertices' positions
    given to the constructor: update(v) returns the surface of geofair.fair of that input
    within the tolerance wherever fair converges (the conformal inner fairness weights and the
    bounding box of the residual's length read the free rows, as fair does).
    
    Parameters
    ----------
    vertices : (n, 3) float64 array, positions in mesh units.
    faces : (m, 3) integer array, consistently oriented triangles.
    free : (n,) bool array, True where a vertex may move.
    details : False (default): the region is the fair surface itself. True: detail
        preservation (Kobbelt et al. 1998, Botsch & Kobbelt 2004): the region is split into its
        own faired base (Δ_B H = 0 with the input's boundary and handle) and the details, the
        input's offsets from the base in the base's local frames (normal and a tangent from a
        neighbour edge); every update adds them back onto the new base (its residual and folds
        are the base's), and live.result at the start is the input itself.
    max_warm_steps : int >= 1 (default 8), Newton steps each warm start of a frame may take
        (from the secant predictor, then where that does not converge from the harmonic one)
        before the frame runs the cold path; a frame's .iterations counts both starts' steps.
    remesh : False (default; also "off"): the region keeps the input's triangles in every frame.
        "if_needed": connectivity that follows the drag. A frame whose warm start does not
        converge, or converges with more folded edges than the input had, is remeshed, and so
        is the frame after one whose smallest triangle angle fell below 1/3 of that of the last
        frame solved anew (the constructor's or a remesh's; squeezed triangles fold a few frames
        later):
        geofair.remesh_region's remesh of the last converged frame's surface, its new free
        vertices moved with the fixed ones to the frame (their harmonic extension), and solved
        warm from there (Newton's method on the new mesh; taken where it converges with no more
        folds than the input had); where that fails, faired cold with the frame's fixed positions
        (where that folds or does not converge, remeshed once more at 4/5 of the edge length).
        It is taken where it converged (with fewer folds than
        the warm start's, where that converged); a remesh that leaves folds is tried again three
        frames later at the earliest. The result's .remeshed, .faces, .free, .unreferenced and
        .origin_face (into the last frame's faces) say so, and later frames start warm on the
        new mesh, whose result is their input's reference (the conformal weights' too). The
        fixed vertices keep their rows; new free vertices take free rows the remesh leaves over,
        then appended rows (n' >= n rows); rows left in no face keep their last positions. The
        constructor fairs the input's own triangles. Not with details=True (its details are
        coded per vertex of the input).
    boundary, boundary_normals, polygon_ids, inner_fairness, outer_fairness, normal_weighting,
    tolerance, max_iterations, damping, cg_iterations, levels, iteration, time_limit, tuning :
        as for geofair.fair; boundary_normals are those of the constructor's vertices (an
        update estimates them unless given its own); iteration, levels and time_limit apply to
        the cold solves (the warm start is Newton's method on the region alone).
    
    Attributes
    ----------
    result : the last converged frame's FairingResult (the constructor's cold fair until then).
    frames, cold_frames, remeshes : updates finished so far, those that ran the cold path, and
        those that replaced the region's triangles (remesh="if_needed").
    
    Raises
    ------
    geofair.InvalidInputError (a ValueError) and geofair.SolverError (a RuntimeError) as
    geofair.fair; InvalidInputError for max_warm_steps < 1, remesh=True ("always"), or
    remesh="if_needed" with details=True; SolverError with details=True where
    the input's base (its cold fair) did not converge.
    """
    def __init__(self, vertices: numpy.typing.NDArray[numpy.float64], faces: numpy.typing.NDArray[numpy.integer[typing.Any]], free: numpy.typing.NDArray[numpy.bool_], *, details: bool = False, max_warm_steps: typing.SupportsInt | typing.SupportsIndex = 8, remesh: bool | typing.Literal['off', 'if_needed'] = False, boundary: typing.Literal['g1', 'g0'] = 'g1', boundary_normals: numpy.typing.NDArray[numpy.float64] | None = None, polygon_ids: numpy.typing.NDArray[numpy.integer[typing.Any]] | None = None, inner_fairness: typing.Literal['uniform', 'conformal', 'conformal_intrinsic'] = 'uniform', outer_fairness: typing.Literal['intrinsic', 'bilaplacian'] = 'intrinsic', normal_weighting: typing.Literal['area', 'angle', 'max', 'quadric'] = 'quadric', tolerance: typing.SupportsFloat | typing.SupportsIndex = 0.0001, max_iterations: typing.SupportsInt | typing.SupportsIndex = 20000, damping: typing.SupportsFloat | typing.SupportsIndex = 0.9, cg_iterations: typing.SupportsInt | typing.SupportsIndex = 10, levels: typing.SupportsInt | typing.SupportsIndex = 0, iteration: typing.Literal['auto', 'newton', 'paper'] = 'auto', time_limit: typing.SupportsFloat | typing.SupportsIndex | None = None, tuning: dict[str, typing.Any] | None = None) -> None:
        ...
    def __repr__(self) -> str:
        ...
    def update(self, vertices: numpy.typing.NDArray[numpy.float64], boundary_normals: numpy.typing.NDArray[numpy.float64] | None = None, time_limit: typing.SupportsFloat | typing.SupportsIndex | None = None) -> FairingResult:
        """
        Fair the region for new positions of its fixed vertices, starting from the last
        converged frame (see LiveFairing).
        
        Parameters
        ----------
        vertices : (n, 3) float64 array, mesh units, n as at construction or, after a remesh, the
            live mesh's n' rows (.result.vertices): the rows of fixed vertices are the frame's
            positions (the handle's and the surroundings'); the rows of free vertices are not read
            (any values, NaN too).
        boundary_normals : (n, 3) float64 unit normals read at the G1 boundary vertices (the
            handle's included), or None (default): estimated from vertices as geofair.fair does.
        time_limit : seconds the frame may take (float > 0; an interactive drag's bound), or None,
            0 or inf (default None): no bound beyond the constructor's time_limit on the cold path.
            The warm start stops before a Newton step once it is spent; a remesh and the cold path
            stop at it too (.stop_reason "time_limit"; the constructor's time_limit, automatic or
            not, still applies to them); where nothing is left for them, the frame is returned
            unconverged without them (.stop_reason "time_limit"), its free rows the last converged
            frame's, its .residual and .folds evaluated there.
        
        Returns
        -------
        FairingResult as geofair.fair's for the frame's input: .vertices (n', 3) (the live mesh's
        rows; n' = n unless remesh="if_needed" replaced the triangles) with the fixed rows
        bit-identical to vertices; .message says how the frame was solved ("warm start from the
        last frame (k Newton steps)", "remeshed from the last frame (...)", or "cold path (fair):
        the warm start did not converge (...)"). A frame that did not converge even on the cold path is returned unconverged, with the
        reason in .message, and leaves .result and the next warm start at the last converged frame.
        
        Raises
        ------
        geofair.InvalidInputError (a ValueError) if vertices has another number of rows than at
        construction (or than the live mesh after a remesh), a fixed vertex of a triangle has a non-finite coordinate (the vertex is
        named), for boundary_normals as geofair.fair, or for a negative or NaN time_limit;
        geofair.SolverError (a RuntimeError) where the cold path raises. Either leaves the state as
        it was.
        """
    @property
    def cold_frames(self) -> int:
        """
        Finished updates that ran the cold path (geofair.fair).
        """
    @property
    def frames(self) -> int:
        """
        Updates finished so far (returned, converged or not).
        """
    @property
    def remeshes(self) -> int:
        """
        Finished updates that replaced the region's triangles (remesh="if_needed").
        """
    @property
    def result(self) -> FairingResult:
        """
        A copy of the last converged frame's FairingResult (the constructor's cold fair until then, converged or not).
        """
def boundary_loops(vertices: numpy.typing.NDArray[numpy.float64], faces: numpy.typing.NDArray[numpy.integer[typing.Any]]) -> list[numpy.typing.NDArray[numpy.int32]]:
    """
    The boundary loops (holes) of a triangle mesh.
    
    Parameters
    ----------
    vertices : (n, 3) float64 array; faces : (m, 3) integer array, consistently oriented, manifold.
    
    Returns
    -------
    list of (k,) int32 arrays, one per loop, its vertices in the direction of the missing face
    (a followed by b: the mesh has a triangle with the edge b -> a), so a triangle (a, b, c)
    added into the hole is oriented like its neighbours; empty for a closed mesh. Every border
    is a loop, an open mesh's outer border too (geofair.holes_to_fill tells holes from outer
    borders).
    
    Raises
    ------
    geofair.InvalidInputError (a ValueError) for invalid triangles or a vertex on two loops (holes that touch).
    """
def boundary_normals(vertices: numpy.typing.NDArray[numpy.float64], faces: numpy.typing.NDArray[numpy.integer[typing.Any]], free: numpy.typing.NDArray[numpy.bool_], *, method: typing.Literal['quadric', 'area'] = 'quadric') -> numpy.typing.NDArray[numpy.float64]:
    """
    The unit normals fair() prescribes at the G1 boundary when it is given no
    boundary_normals: estimated from the fixed surface around the free region (beyond the
    paper; Schneider & Kobbelt 2001, section 7.5, average the outside triangles' normals).
    
    The G1 boundary is the set of fixed vertices that share a triangle with a free vertex; a
    vertex's surrounding triangles are its triangles without a free vertex (the positions of
    free vertices, which fairing replaces, never enter).
    
    Parameters
    ----------
    vertices : (n, 3) float64 array, positions in mesh units.
    faces : (m, 3) integer array, consistently oriented triangles.
    free : (n,) bool array, True where a vertex may move.
    method : "quadric" (default): the tangent plane of a least-squares paraboloid
        z = a x + b y + c x² + d xy + e y² through the vertex, fitted to the fixed vertices
        within two rings reached through surrounding triangles, in the frame of the "area"
        normal and refitted once in the fitted normal's frame; error O(h²) for edge length h on
        a smooth surface (falls back to "area" where the fit is ill-conditioned: fewer than 6
        samples, condition number above 1e6, e.g. only two straight rows of fixed vertices, or
        a tilt of 45° or more). "area": the area-weighted normal of the surrounding
        triangles, one-sided, error O(h) (fair()'s estimate before this release). Measured in
        tests/test_boundary_normals.py.
    
    Returns
    -------
    (n, 3) float64: unit normals at G1 boundary vertices, oriented like the faces (positive
    dot product with the surrounding triangles' normal); zero rows at all other vertices and at
    G1 boundary vertices without a surrounding triangle (where the free region reaches the
    mesh border: fair() without boundary_normals raises there) or with only degenerate ones.
    
    Raises
    ------
    geofair.InvalidInputError (a ValueError) for invalid input (shapes, dtypes, indices, a
    non-finite vertex of a
    surrounding triangle).
    """
def cotangent_laplacian(vertices: numpy.typing.NDArray[numpy.float64], faces: numpy.typing.NDArray[numpy.integer[typing.Any]]) -> scipy.sparse.csr_matrix:
    """
    The cotangent Laplace–Beltrami matrix L of a triangle mesh (Schneider & Kobbelt
    2001, eqs. (5)-(7)) as an (n, n) scipy.sparse CSR matrix (needs scipy).
    
    L[i, j] = cot α_ij + cot β_ij for every edge (a single cotangent on a border edge) and
    L[i, i] = -Σ_j L[i, j]: symmetric, L @ ones = 0. (L @ f)[i] = (2 A_i / 3) Δ_B f(q_i) with A_i
    the area of the 1-disk, so L @ vertices = -(4 A_i / 3) H_i n_i; the matrix S of eqs. (6),
    (7) is -L restricted to the free rows and columns.
    
    Raises geofair.InvalidInputError (a ValueError) for invalid input.
    """
def defaults() -> dict[str, typing.Any]:
    """
    The defaults of geofair.fair's keyword arguments, the library's one source of them:
    geofair.fair(vertices, faces, free, **geofair.defaults()) is fair's default call.
    
    Returns
    -------
    dict, a new one per call, in the order of fair's signature: "remesh" (False),
    "boundary", "inner_fairness", "outer_fairness", "normal_weighting", "iteration" (str),
    "boundary_normals", "polygon_ids", "progress", "time_limit" (None; None or 0 is the
    automatic time limit), "tolerance" (float, dimensionless), "max_iterations",
    "cg_iterations", "levels" (int), "damping" (float), and "tuning": a dict of the solvers'
    numerical choices beyond the paper by dotted name, e.g. "newton.patience" or
    "schedule.time_limit_base" (seconds; the automatic time limit's figures), which fair's
    tuning=None means (units and ranges: native/include/geofair/tuning.h).
    """
def fair(vertices: numpy.typing.NDArray[numpy.float64], faces: numpy.typing.NDArray[numpy.integer[typing.Any]], free: numpy.typing.NDArray[numpy.bool_], *, remesh: bool | typing.Literal['off', 'always', 'if_needed'] = False, boundary: typing.Literal['g1', 'g0'] = 'g1', boundary_normals: numpy.typing.NDArray[numpy.float64] | None = None, polygon_ids: numpy.typing.NDArray[numpy.integer[typing.Any]] | None = None, inner_fairness: typing.Literal['uniform', 'conformal', 'conformal_intrinsic'] = 'uniform', outer_fairness: typing.Literal['intrinsic', 'bilaplacian'] = 'intrinsic', normal_weighting: typing.Literal['area', 'angle', 'max', 'quadric'] = 'quadric', tolerance: typing.SupportsFloat | typing.SupportsIndex = 0.0001, max_iterations: typing.SupportsInt | typing.SupportsIndex = 20000, damping: typing.SupportsFloat | typing.SupportsIndex = 0.9, cg_iterations: typing.SupportsInt | typing.SupportsIndex = 10, levels: typing.SupportsInt | typing.SupportsIndex = 0, iteration: typing.Literal['auto', 'newton', 'paper'] = 'auto', progress: collections.abc.Callable[[int, float], bool | None] | None = None, time_limit: typing.SupportsFloat | typing.SupportsIndex | None = None, tuning: dict[str, typing.Any] | None = None) -> FairingResult:
    """
    Fair the free vertices of a triangle mesh: the discrete solution of Δ_B H = 0
    (Schneider & Kobbelt 2001, eqs. (4) and (12), solved as in section 7) with the G1 boundary
    condition (fixed positions and unit normals) at the fixed vertices next to free ones, or with
    boundary="g0" the G0 condition (fixed positions, H = 0). Every option in detail:
    docs/REFERENCE.md, "The options of geofair.fair".
    
    Parameters
    ----------
    vertices : (n, 3) float64 array, positions in mesh units.
    faces : (m, 3) integer array, triangles counter-clockwise seen from the normal side, a
        consistently oriented manifold around the free region.
    free : (n,) bool array, True where a vertex may move (not on the mesh border). The fixed
        vertices that share a triangle with a free one form the boundary.
    remesh : False (default; also "off"): the triangles are kept. True (also "always"): the
        region's triangles are first replaced by geofair.remesh_region's isotropic remesh.
        "if_needed": remeshed and faired again only where the kept triangles do not converge
        or fold over.
    boundary : "g1" (default): positions and unit normals prescribed (section 4). "g0":
        positions only and H = 0: the minimal surface spanned by the boundary.
    boundary_normals : (n, 3) float64 unit normals, read at the G1 boundary vertices, oriented
        like the faces; None (default): geofair.boundary_normals(vertices, faces, free).
    polygon_ids : (m,) integer array, the polygon each triangle was cut from: "uniform" inner
        fairness runs over the polygons' edges; None (default): over the triangles' edges.
    inner_fairness : where the vertices sit on the surface (section 7.3): "uniform" (default,
        a regular distribution), "conformal" (the input's cotangent weights: low UV distortion)
        or "conformal_intrinsic" (those of the input's intrinsic Delaunay triangulation).
    outer_fairness : "intrinsic" (default, Δ_B H = 0) or "bilaplacian" (the linear Δ²f = 0
        initial mesh of section 7.4 alone).
    normal_weighting : the free vertices' normals (section 6): "quadric" (default, the tangent
        plane of a least-squares quadric), "area" (the paper's), "angle" or "max".
    tolerance : stop once the residual is at most this (default 0.0001, dimensionless): the
        residual is L max_i |Hbar_i - H_i| over the free vertices, Hbar_i the cotangent-weighted
        mean of the neighbours' H (eq. (12) scaled), L the region's bounding-box diagonal.
    max_iterations : iterations at most on each level, and Newton steps (default 20000).
    damping : s in q <- q~ + s t n (section 7.2), in (0, 1] (default 0.9).
    cg_iterations : conjugate-gradient iterations of a global step (section 7.1, default 10).
    levels : levels of the progressive-mesh multigrid (section 7.4): 0 (default) picks them from
        the region, 1 solves the region as one level.
    iteration : how eq. (12) is solved, the same equations each: "auto" (default: "newton",
        then "paper" where it stops unconverged), "newton" (Newton's method on all free vertices
        at once, beyond the paper) or "paper" (section 7's iteration with multigrid cycles).
    progress : callable(iteration, residual) -> bool, or None; called at most every 0.1 s,
        returning False stops the solve (stop_reason "cancelled").
    time_limit : None or 0 (default): automatic. With iteration="auto" the solve stops once the
        residual has not halved for 5 s plus 0.2 ms per free vertex, and after
        5 times that in any case; "newton" and "paper" run to max_iterations. A number > 0:
        the seconds the whole call may take (float("inf"): no limit).
    tuning : dict or None: numerical choices beyond the paper by dotted name, e.g.
        "newton.patience": 40; the names and defaults: geofair.defaults()["tuning"].
    
    Returns
    -------
    FairingResult, whose fields are
        vertices : (n', 3) float64, fixed rows bit-identical to the input; n' = n unless remeshed.
        faces : (m', 3) int32 and free : (n',) bool, the input's unless remeshed.
        remeshed : bool; unreferenced : (k,) int32, rows in no face; origin_face : (n',) int32
            and origin_barycentric : (n', 3) float64, where each new free vertex lay on the
            input (-1 and zeros for the other rows, and unless remeshed).
        converged : bool, residual <= tolerance; residual : float, dimensionless.
        message : str, how the solve ended: one sentence with the residual and the tolerance.
        stop_reason : str, "converged", "max_iterations", "time_limit", "no_progress" (the
            automatic limit), "cancelled" (progress returned False) or "diverged" (the input is
            returned).
        iterations : int, all levels; iterations_per_level, vertices_per_level : lists, coarsest
            level first; iteration : "newton" or "paper"; newton_iterations : int.
        folds : int, edges with a free vertex whose two triangles face apart; new_folds : int,
            those not folded in the input.
        phase_seconds : list of (phase, seconds), wall-clock time per phase.
    
    Raises
    ------
    geofair.InvalidInputError (a ValueError): invalid input or option value; the message names
        the problem and the vertex, face or option (a mesh whose squared lengths leave the
        normal doubles, with a bounding-box diagonal above about 1.3e154 or a mean edge length
        below about 1.5e-154, names its size). Within those sizes the result is the same at any
        scale (positions are worked on in units of the mesh's own size).
    geofair.SolverError (a RuntimeError): the computation failed or diverged. NaN or Inf is
        never returned.
    TypeError: an unknown keyword argument, or an argument of the wrong type.
    """
def fill_holes(vertices: numpy.typing.NDArray[numpy.float64], faces: numpy.typing.NDArray[numpy.integer[typing.Any]], loops: collections.abc.Iterable[collections.abc.Iterable[typing.SupportsIndex]] | None = None, *, target_edge_length: typing.SupportsFloat | typing.SupportsIndex | None = None, keep_outer_borders: bool = True, max_hole_edges: typing.SupportsInt | typing.SupportsIndex | None = None, rim: typing.Literal['keep', 'trim'] = 'keep', boundary: typing.Literal['g1', 'g0'] = 'g1', inner_fairness: typing.Literal['uniform', 'conformal', 'conformal_intrinsic'] = 'uniform', outer_fairness: typing.Literal['intrinsic', 'bilaplacian'] = 'intrinsic', normal_weighting: typing.Literal['area', 'angle', 'max', 'quadric'] = 'quadric', tolerance: typing.SupportsFloat | typing.SupportsIndex = 0.0001, max_iterations: typing.SupportsInt | typing.SupportsIndex = 20000, damping: typing.SupportsFloat | typing.SupportsIndex = 0.9, cg_iterations: typing.SupportsInt | typing.SupportsIndex = 10, levels: typing.SupportsInt | typing.SupportsIndex = 0, iteration: typing.Literal['auto', 'newton', 'paper'] = 'auto', progress: collections.abc.Callable[[int, float], bool | None] | None = None, time_limit: typing.SupportsFloat | typing.SupportsIndex | None = None, tuning: dict[str, typing.Any] | None = None) -> FillResult:
    """
    Fill holes of a triangle mesh with intrinsically faired patches: each hole's
    loop keeps its positions and takes its unit normals from the faces around it (the G1
    boundary of Schneider & Kobbelt 2001, section 4; estimated as geofair.boundary_normals
    does), and the patch solves Δ_B H = 0 (eq. (12)), so a hole cut into a sphere, cylinder
    or catenoid is filled with that surface (beyond the paper: the triangulation and refinement).
    
    Each hole's loop is triangulated (Liepa's dynamic programme, Liepa 2003, "Filling holes
    in meshes", by the largest dihedral angle between adjacent triangles, the faces around the
    loop included, then the area; loops of more than 500 vertices get a fan around their
    centroid), the edges across the hole are split, the patch is remeshed isotropically at
    target_edge_length (geofair.remesh_region), and faired by geofair.fair with the new
    vertices free, each hole on its own (its patch and the faces within three rings of its loop).
    
    Every hole gets a fill: per hole the fills below are tried in order and the first that
    converges without a folded edge is kept, else the one with the fewest folded edges
    (converged first among equals): "intrinsic" (the fill above), "intrinsic_trimmed"
    (rim="trim" only, where the rim has something to trim: the rim's teeth, triangles with two
    loop edges, and the triangles at loop vertices whose faces span less than 90° removed, up to
    three rounds, while the hole stays one simple loop; MeshFix's remove-and-fill, Attene
    2010; then, where the fill still folds, the input triangles that fold against it, up to
    three rounds; at most as many faces as the loop has vertices), "intrinsic_finer" (at half
    the loop's edge length, on the input's rim and then on the trimmed one, where
    target_edge_length is None and the first fill has at most 5000 new vertices: ragged loops
    need a finer fill next to them), "g0" (positions only at the loop: the minimal surface) and "linear" (the linear
    Δ²f = 0 fill of the same patch, the method of CGAL's triangulate_refine_and_fair_hole; the
    last two on the last trimmed rim where it was trimmed). .holes says which fill each hole got.
    A hole is left open only where no fill can be made (over 2000000 new vertices).
    
    Parameters
    ----------
    vertices : (n, 3) float64 array, positions in mesh units.
    faces : (m, 3) integer array, triangles, consistently oriented, manifold.
    loops : None (default): the holes of geofair.holes_to_fill(vertices, faces,
        keep_outer_borders=..., max_hole_edges=...), every boundary loop but the outer borders
        of open surfaces (the result's .message names the loops left open and why); or a list
        of loops, each a sequence of vertex indices along one boundary loop (any start vertex,
        either direction), filled whatever their size.
    target_edge_length : edge length of the fill in mesh units, or None (default): the mean
        length of the hole's loop edges.
    keep_outer_borders : with loops=None, leave each outer border open (default True): in each
        connected part of the mesh, the boundary loop that spans the largest area (the norm of
        its vector area, ½|Σ (p_i − c) × (p_{i+1} − c)| about the centroid c of its vertices
        p_i), where that is at least 30 % of the area of the part's triangles. A
        sheet's border spans about the sheet's own area (a height field's: its area projected on
        the plane), a hole in a closed surface a small part of it (a sphere missing a cap of
        polar angle θ: (1 − cos θ)/2 of the rest, below 30 % up to θ = 66°). A part has at
        most one outer border: a hole in a sheet is filled whatever its size. False: every
        boundary loop is a hole (an open sheet is then capped into a closed surface). Not read
        when loops are given.
    max_hole_edges : with loops=None, leave loops of more edges than this open (like Blender's
        Fill Holes Sides or MeshLab's Close Holes size); None (default): no limit.
    rim : "keep" (default): every input face is kept; "trim": where the fill of a loop as it is
        folds or does not converge, input faces at its rim may be removed first (see above; named
        in .removed_faces and each hole's .removed_faces).
    boundary, inner_fairness, outer_fairness, normal_weighting, tolerance, max_iterations,
    damping, cg_iterations, levels, iteration, progress, time_limit, tuning : as for
        geofair.fair (time_limit covers the filling too), except that each fill's fair takes
        max_iterations (iterations per level) at most tuning "schedule.fill_max_iterations"
        (2000), so that a fill that does not converge gives way to the next (its
        attempt then reports "did not converge within max_iterations"); boundary="g0" fills
        with the minimal surface spanned by the loop.
    
    Returns
    -------
    FillResult (a FairingResult): .vertices (n + k, 3), the input's n rows first and
    bit-identical, the k new vertices after (with rim="trim", input rows whose every face was
    removed stay, listed in .unreferenced); .faces, the input's m faces first and unchanged
    (with rim="trim" less .removed_faces, the others in their order), then each hole's fill,
    oriented like the faces around the holes; .free (n + k,) bool, True exactly at the new
    vertices; .remeshed True (.origin_face -1: a fill has no input surface); .converged (every
    fill converged), .residual (the largest), .folds and .new_folds (the fills' folded edges,
    HoleFill.folds, summed), .message (one clause per method), .stop_reason and .phase_seconds
    (starting with "fill", the holes' phases summed); .holes, a list of geofair.HoleFill (loop,
    method, converged, folds, removed_faces, attempts, reason), the holes in the order of the
    loops, then the loops the rule left open; .removed_faces (r,) int32, sorted.
    
    Raises
    ------
    geofair.InvalidInputError (a ValueError) when loops is not a list of sequences of vertex
    indices, a loop is not a boundary loop of the mesh (the offending pair of vertices is named),
    a vertex is on two given loops, rim is not "keep" or "trim", the mesh has no hole to fill (no boundary loop, or with
    loops=None every loop is left open: the message names them and why), max_hole_edges is not
    None or a positive integer, no hole can be filled under 2000000 new vertices, the mesh's
    squared lengths leave the normal doubles (a bounding-box diagonal above about 1.3e154 or a
    mean edge length below about 1.5e-154: the message names the size), or for the input fair
    refuses (the message names the problem and the vertex or face); geofair.SolverError (a
    RuntimeError) as fair. Within those sizes the fill is the same at any scale (positions are
    worked on in units of the mesh's own size).
    """
def holes_to_fill(vertices: numpy.typing.NDArray[numpy.float64], faces: numpy.typing.NDArray[numpy.integer[typing.Any]], *, keep_outer_borders: bool = True, max_hole_edges: typing.SupportsInt | typing.SupportsIndex | None = None) -> tuple[list[numpy.typing.NDArray[numpy.int32]], list[tuple[numpy.typing.NDArray[numpy.int32], str]]]:
    """
    The holes that geofair.fill_holes fills when it is given no loops: the boundary
    loops of the mesh (geofair.boundary_loops) less those the rule leaves open.
    
    Parameters
    ----------
    vertices : (n, 3) float64 array, positions in mesh units; faces : (m, 3) integer array,
        consistently oriented, manifold.
    keep_outer_borders : leave each outer border open (default True): in each connected part,
        the boundary loop that spans the largest area, where that is at least 30 % of the
        area of the part's triangles (see geofair.fill_holes). False: every boundary loop is a
        hole.
    max_hole_edges : leave loops of more edges than this open; None (default): no limit.
    
    Returns
    -------
    (holes, left_open): holes a list of (k,) int32 arrays, the loops to fill as
    geofair.boundary_loops returns them (in its order); left_open a list of (loop, reason)
    tuples, the other loops with one clause for a user saying why (e.g. "an outer border: it
    spans 95 % of the area of its part's triangles (a hole less than 30 %)"; a piece of border
    that passes more than once through a vertex, where holes touch: "not a simple loop: ...",
    its vertices sorted). Both empty for
    a closed mesh. The same at any scale of the mesh.
    
    Raises
    ------
    geofair.InvalidInputError (a ValueError) as geofair.boundary_loops, for max_hole_edges not
    None or a positive integer, or a mesh whose squared lengths leave the normal doubles (see
    geofair.fill_holes).
    """
def intrinsic_delaunay(vertices: numpy.typing.NDArray[numpy.float64], faces: numpy.typing.NDArray[numpy.integer[typing.Any]]) -> tuple[numpy.typing.NDArray[numpy.int32], numpy.typing.NDArray[numpy.float64], int]:
    """
    Intrinsic Delaunay triangulation of a triangle mesh by edge flips (Fisher et al.
    2006; Bobenko & Springborn 2007): same vertices, same surface, other edges (geodesics on
    the mesh) such that the two angles opposite every interior edge sum to at most π.
    
    Returns
    -------
    (triangles, lengths, flips): (m, 3) int32 vertex indices (counter-clockwise like faces; a
    triangle may repeat a vertex), (m, 3) float64 edge lengths in mesh units (lengths[t, k]
    from corner k to corner k+1 of triangle t), and the number of flips (0 if the mesh was
    intrinsically Delaunay).
    
    Raises geofair.InvalidInputError (a ValueError) for invalid input, geofair.SolverError (a
    RuntimeError) if round-off made the flips cycle.
    """
def intrinsic_delaunay_laplacian(vertices: numpy.typing.NDArray[numpy.float64], faces: numpy.typing.NDArray[numpy.integer[typing.Any]]) -> scipy.sparse.csr_matrix:
    """
    The cotangent Laplacian of the intrinsic Delaunay triangulation (Bobenko &
    Springborn 2007) as an (n, n) scipy.sparse CSR matrix, with the conventions of
    cotangent_laplacian: L[i, j] = Σ cot of the angles opposite the intrinsic edges between
    i and j, L[i, i] = -Σ_j L[i, j]. Every off-diagonal entry is >= 0 (to round-off), unlike
    the cotangent Laplacian of a mesh with obtuse triangles; equal to cotangent_laplacian
    where the mesh is already intrinsically Delaunay.
    
    Raises geofair.InvalidInputError (a ValueError) for invalid input.
    """
def mean_curvature(vertices: numpy.typing.NDArray[numpy.float64], faces: numpy.typing.NDArray[numpy.integer[typing.Any]], normals: numpy.typing.NDArray[numpy.float64] | None = None, normal_weighting: typing.Literal['area', 'angle', 'max', 'quadric'] = 'quadric') -> numpy.typing.NDArray[numpy.float64]:
    """
    Discrete mean curvature at every vertex by Moreton & Séquin (Schneider & Kobbelt
    2001, section 6, eqs. (8)-(11)), with the spiral samples of section 6.2 at vertices of
    valence 3 or 4 and on the mesh border.
    
    Parameters
    ----------
    vertices : (n, 3) float64 array.
    faces : (m, 3) integer array of consistently oriented triangles.
    normals : (n, 3) float64 unit normals (tangent planes) or None to estimate them from the
        triangles with `normal_weighting` ("quadric", the default: tangent plane of a
        least-squares quadric through the one-ring; "area", the paper's choice; "angle" or
        "max").
    
    Returns
    -------
    (n,) float64 mean curvature in 1/length: H = 1/r on a sphere of radius r whose faces are
    oriented outward, 1/(2r) on a cylinder, 0 on a plane; 0 at vertices in no triangle.
    
    Raises
    ------
    geofair.InvalidInputError (a ValueError) for invalid input.
    """
def progressive_mesh(vertices: numpy.typing.NDArray[numpy.float64], faces: numpy.typing.NDArray[numpy.integer[typing.Any]], free: numpy.typing.NDArray[numpy.bool_], levels: typing.SupportsInt | typing.SupportsIndex = 1, coarsen_boundary: bool = False) -> list[numpy.typing.NDArray[numpy.int32]]:
    """
    The progressive-mesh hierarchy that fair() uses for its multigrid (Schneider &
    Kobbelt 2001, section 7.4): a list of (m_l, 3) int32 triangle arrays in the input's vertex
    indices, coarsest level first, the last being the region (triangles with a free vertex)
    itself. Levels are nested (the vertex set of each is a subset of the next).
    
    coarsen_boundary=False: the hierarchy of the paper's iteration (iteration="paper"): G1
    boundary vertices are never collapsed, free vertices keep valences 5..8 through the
    collapses, and a coarse level keeps at least half as many free vertices as there are boundary
    vertices. True: the hierarchy of Newton's method (iteration="newton", the default path):
    boundary vertices collapse too, along the region's border into a neighbour on it (each border
    loop keeps at least 12 vertices; a fixed vertex inside the region never collapses), free
    vertices keep valences 4..10, those of valence 3 and 4 collapse first, and level l keeps about
    (free + boundary vertices) / 4^(levels-1-l) vertices.
    
    Measured on the input smoothed by 10 sweeps of the uniform Laplacian (fair() smooths with its
    inner fairness weights).
    
    Raises geofair.InvalidInputError (a ValueError) for invalid input.
    """
def read_mesh(path: str) -> dict[str, typing.Any]:
    """
    Read an OBJ, PLY, OFF or STL file (by its extension) with OpenMesh's readers.
    
    Parameters
    ----------
    path : str, the file.
    
    Returns
    -------
    dict: "vertices" (n, 3) float64 positions in file units (OpenMesh's readers keep single
    precision: about 1e-7 relative); "faces" (m, 3) int32 triangles
    (polygons split into fans, oriented as in the file); "polygon" (m,) int32 the file's face of
    each triangle; "colors" (n, 4) uint8 RGBA vertex colours (PLY, OFF) or None; "texcoords"
    (n, 2) float64 vertex texture coordinates (OBJ's vt) or None. STL's repeated corners are
    merged into shared vertices.
    
    Raises
    ------
    geofair.InvalidInputError (a ValueError) naming the file and the problem: an unknown
    extension, an unreadable file, faces OpenMesh's reader skips as non-manifold, no face, or a
    non-finite coordinate.
    """
def relax_inner_fairness(vertices: numpy.typing.NDArray[numpy.float64], faces: numpy.typing.NDArray[numpy.integer[typing.Any]], free: numpy.typing.NDArray[numpy.bool_], normals: numpy.typing.NDArray[numpy.float64], inner_fairness: typing.Literal['uniform', 'conformal', 'conformal_intrinsic'] = 'uniform', tangent_planes: typing.Literal['fixed', 'turning'] = 'turning', polygon_ids: numpy.typing.NDArray[numpy.integer[typing.Any]] | None = None) -> tuple[numpy.typing.NDArray[numpy.float64], float]:
    """
    One global tangential solve of inner fairness, the step fair()'s Newton iteration
    repeats (Schneider & Kobbelt 2001, section 7.3's condition, linearized for all free
    vertices at once; beyond the paper): every free vertex moves in its tangent plane so that
    the tangential part of the inner-fairness Laplacian Σ_j λ_ij q_j − q_i vanishes, the whole
    move scaled so that no edge stretches or shrinks by more than half its length. The
    vertices are not lifted back onto the surface.
    
    Parameters
    ----------
    vertices : (n, 3) float64 array; faces : (m, 3) integer array; free : (n,) bool mask, as
        for fair() (the region and its G1 boundary).
    normals : (n, 3) float64 normals of the tangent planes (rows of free vertices and their
        ring neighbours are read; normalized here).
    inner_fairness : "uniform" (default), "conformal" or "conformal_intrinsic", the weights
        of the mesh as given.
    tangent_planes : "turning" (default): Newton's linearization, with the first-order turn of
        each tangent plane as its vertex moves along the surface (the normal part ℓ_i of the
        Laplacian vector times the normal's derivative D_i, fitted to the ring's normals, on
        the diagonal blocks); repeated solves converge quadratically. "fixed": the tangent
        planes held fixed (section 7.3's update, all vertices at once); repeated solves
        converge linearly.
    polygon_ids : (m,) integer array or None, as for fair(): uniform weights over the polygon
        mesh's edges.
    
    Returns
    -------
    (vertices, scale): (n, 3) float64 positions (free rows moved, mesh units) and the scale in
    (0, 1] applied to the solved move.
    
    Raises geofair.InvalidInputError (a ValueError) for invalid input, geofair.SolverError (a
    RuntimeError) if the system is
    singular.
    """
def remesh_region(vertices: numpy.typing.NDArray[numpy.float64], faces: numpy.typing.NDArray[numpy.integer[typing.Any]], free: numpy.typing.NDArray[numpy.bool_], *, target_edge_length: typing.SupportsFloat | typing.SupportsIndex | None = None, iterations: typing.SupportsInt | typing.SupportsIndex = 5) -> RemeshedRegion:
    """
    Isotropic remesh of a region of a triangle mesh (Botsch & Kobbelt 2004, "A
    remeshing approach to multiresolution modeling", section 4), the step fair(remesh=...)
    runs before fairing: the region's triangles (those with a free vertex) are replaced, the
    fixed vertices and the region's border edges are kept.
    
    Each iteration splits edges longer than 4/3 L, collapses edges shorter than 4/5 L (a free
    vertex into a neighbour; never one that would create an edge longer than 4/3 L), flips
    interior edges towards valence 6 (4 on the mesh border, counting the edges outside the
    region), and moves each free vertex to the area-weighted centroid of its one-ring in its
    tangent plane. Every new or moved vertex is projected onto the closest point of the input
    region's triangles. No step turns a triangle over, leaves it thinner (twice the area over
    the longest edge squared) than 0.05 and than the triangle it replaces, or puts a vertex on
    the region's border; such a step is skipped.
    
    Parameters
    ----------
    vertices : (n, 3) float64 array, positions in mesh units.
    faces : (m, 3) integer array, triangles; those with a free vertex must form a consistently
        oriented 2-manifold.
    free : (n,) bool array, True where a vertex may move (not on the mesh border).
    target_edge_length : float > 0 in mesh units, or None (default): the mean length of the
        region's border edges (of all its edges where it has no border).
    iterations : int >= 0, rounds of split, collapse, flip and relaxation (0: the input).
    
    Returns
    -------
    RemeshedRegion with .vertices (n', 3) float64, .faces (m', 3) int32 (the faces without a
    free vertex unchanged and first, then the new ones), .free (n',) bool, .unreferenced (k,)
    int32, .origin_face (n',) int32 and .origin_barycentric (n', 3) float64 (where each free
    vertex lies on the input surface). Rows of fixed vertices keep their index and position
    bit-identically; a surviving input free vertex keeps its row, the other new free vertices
    take the remaining input free rows in increasing order, then rows appended after n, so
    n' = max(n, #fixed + #new free); free rows left over are listed in .unreferenced.
    
    Raises
    ------
    geofair.InvalidInputError (a ValueError) for invalid input (shapes, indices, no free vertex, a free vertex on the mesh
    border, a region that is not a consistently oriented 2-manifold, invalid options).
    """
def write_mesh(path: str, vertices: numpy.typing.NDArray[numpy.float64], faces: numpy.typing.NDArray[numpy.integer[typing.Any]], *, colors: numpy.typing.NDArray[numpy.uint8] | None = None, texcoords: numpy.typing.NDArray[numpy.float64] | None = None) -> None:
    """
    Write a triangle mesh to an OBJ, PLY (binary), OFF or STL (binary) file (by its
    extension) with OpenMesh's writers, positions in single precision (about 1e-7 relative).
    The file is written under a temporary name beside the destination and renamed over it at the
    end: an error never leaves a partial file.
    
    Parameters
    ----------
    path : str, the file.
    vertices : (n, 3) float64 positions; faces : (m, 3) integer triangles.
    colors : None or (n, 4) uint8 RGBA vertex colours (written to PLY and OFF).
    texcoords : None or (n, 2) float64 vertex texture coordinates (written to OBJ and PLY; per
        vertex, so a UV seam is not kept).
    
    Raises
    ------
    geofair.InvalidInputError (a ValueError) for an unknown extension, faces that index no
    vertex, a non-finite coordinate, or triangles that do not form a manifold mesh; OSError if
    the file cannot be written.
    """
__version__: str
