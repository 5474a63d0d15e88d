"""
Intrinsic mesh fairing: discrete solutions of Δ_B H = 0 with G1 boundary conditions
(Schneider & Kobbelt, Geometric fairing of irregular meshes for free-form surface
design, CAGD 18, 2001).
"""
from __future__ import annotations
import numpy
import numpy.typing
import scipy.sparse
import typing
__all__: list[str] = ['FairingResult', 'InvalidInputError', 'RemeshedRegion', 'SolverError', 'boundary_loops', 'boundary_normals', 'cotangent_laplacian', 'defaults', 'fair', 'fill_holes', 'holes_to_fill', 'intrinsic_delaunay', 'intrinsic_delaunay_laplacian', 'mean_curvature', 'progressive_mesh', 'relax_inner_fairness', 'remesh_region']
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
    def free(self) -> numpy.ndarray[typing.Any, numpy.dtype[typing.Any]]:
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
    def free(self) -> numpy.ndarray[typing.Any, numpy.dtype[typing.Any]]:
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
    def unreferenced(self) -> numpy.typing.NDArray[numpy.int32]:
        """
        (k,) int32: input free rows that no new vertex reuses (in no face, not free).
        """
    @property
    def vertices(self) -> typing.Annotated[numpy.typing.NDArray[numpy.float64], "[m, 3]"]:
        """
        (n', 3) float64 positions, mesh units; rows of fixed vertices are bit-identical to the input, n' = max(n, #fixed + #new free).
        """
def boundary_loops(vertices: typing.Any, faces: typing.Any) -> list:
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
    ValueError for invalid triangles or a vertex on two loops (holes that touch).
    """
def boundary_normals(vertices: typing.Any, faces: typing.Any, free: typing.Any, *, method: str = 'quadric') -> typing.Annotated[numpy.typing.NDArray[numpy.float64], "[m, 3]"]:
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
    ValueError for invalid input (shapes, dtypes, indices, a non-finite vertex of a
    surrounding triangle).
    """
def cotangent_laplacian(vertices: typing.Any, faces: typing.Any) -> scipy.sparse.csr_matrix:
    """
    The cotangent Laplace–Beltrami matrix L of a triangle mesh (Schneider & Kobbelt
    2001, eqs. (5)-(7)) as an (n, n) scipy.sparse CSR matrix (needs scipy).
    
    L[i, j] = cot α_ij + cot β_ij for every edge (a single cotangent on a border edge) and
    L[i, i] = -Σ_j L[i, j]: symmetric, L @ ones = 0. (L @ f)[i] = (2 A_i / 3) Δ_B f(q_i) with A_i
    the area of the 1-disk, so L @ vertices = -(4 A_i / 3) H_i n_i; the matrix S of eqs. (6),
    (7) is -L restricted to the free rows and columns.
    
    Raises ValueError for invalid input.
    """
def defaults() -> dict:
    """
    The defaults of geofair.fair's options, the library's one source of them.
    
    Returns
    -------
    dict: "inner_fairness", "outer_fairness", "normal_weighting", "iteration" (str),
    "tolerance" (float, dimensionless), "max_iterations", "cg_iterations", "levels" (int),
    "damping" (float), "remesh" (False, True or "if_needed"), "time_limit" (None: automatic),
    the automatic time limit of iteration="auto" (time without a halving of the residual),
    "time_limit_base" (seconds) plus
    "time_limit_per_free_vertex" (seconds per free vertex), its hard cap as a multiple of that,
    "time_limit_hard_factor", and "tuning" (dict: the solvers' numerical choices beyond the paper, by
    dotted name, e.g. "newton.patience"; their units and ranges: native/include/geofair/tuning.h).
    """
def fair(vertices: typing.Any, faces: typing.Any, free: typing.Any, *, remesh: typing.Any = False, boundary: str = 'g1', boundary_normals: typing.Any = None, polygon_ids: typing.Any = None, inner_fairness: str = 'uniform', outer_fairness: str = 'intrinsic', normal_weighting: str = 'quadric', tolerance: typing.SupportsFloat | typing.SupportsIndex = 0.0001, max_iterations: typing.SupportsInt | typing.SupportsIndex = 20000, damping: typing.SupportsFloat | typing.SupportsIndex = 0.9, cg_iterations: typing.SupportsInt | typing.SupportsIndex = 10, levels: typing.SupportsInt | typing.SupportsIndex = 0, iteration: str = 'auto', progress: typing.Any = None, time_limit: typing.Any = None, tuning: typing.Any = None) -> FairingResult:
    """
    Fair the free vertices of a triangle mesh: the discrete solution of Δ_B H = 0
    (Schneider & Kobbelt 2001, eqs. (4), (12), construction of section 7) with the G1 boundary
    condition (fixed positions and unit normals) at the fixed vertices next to free ones, or
    with boundary="g0" the G0 condition (fixed positions, H = 0).
    
    Parameters
    ----------
    vertices : (n, 3) float64 array, positions in mesh units.
    faces : (m, 3) integer array, triangles, consistently oriented (counter-clockwise seen from
        the normal side), manifold around the free region.
    free : (n,) bool array, True where a vertex may move. Each free vertex must be surrounded
        by triangles (not on the mesh border). Fixed vertices that share a triangle with a free
        vertex form the boundary.
    remesh : False (default; also "off"), True (also "always") or "if_needed". False: the
        connectivity is kept (the paper's setting). True: the region's triangles (those with a
        free vertex) are first replaced by geofair.remesh_region's isotropic remesh at the mean
        length of the region's border edges (fixed vertices and the region's border edges
        kept; the G1 normals taken from the input), then faired. "if_needed": faired with the
        connectivity kept first; where that does not converge or folds triangles over that
        were not folded, remeshed and faired again: the remeshed result is returned if it
        converged without new folds, else the better of the two (converged first, then fewer
        new folds, then the smaller residual); .message says which. A remeshed result has
        other vertices and faces: n' rows (fixed rows keep index and position, the input's free
        rows are reused, extra rows appended; .unreferenced lists free rows left over), its
        .faces, .free, and .origin_face / .origin_barycentric locating each new free vertex on
        the input surface (to carry UVs over); its .folds and .new_folds count its own
        triangles (new: not folded in the remesh before fairing). polygon_ids do not apply to
        the new triangles. An explicit time_limit covers the whole call; the automatic one
        applies to each solve.
    boundary : "g1" (default) or "g0". "g1": the paper's G1 condition, positions and unit
        normals (boundary_normals) prescribed at the boundary; spheres, cylinders and minimal
        surfaces that fit the data are reproduced. "g0": positions only, with H = 0 prescribed
        on the boundary; Δ_B H = 0 then gives H ≡ 0, the minimal surface spanned by the
        boundary (a plane for a planar loop, a catenoid between two coaxial circles close
        enough together; the intrinsic counterpart of Blender's Fair Positions and CGAL's fair
        with continuity 0). With "g0" boundary_normals is ignored (not read, not checked),
        nothing is estimated from the surface around the region, so the region may reach the
        mesh border, and the linear initial mesh (and outer_fairness="bilaplacian") is the
        membrane Δf = 0: Δ²f = 0 with Δf = 0 at the boundary, the linear counterpart of H = 0.
        H is signed as in geofair.mean_curvature (H = 1/r on a sphere with outward normals);
        with "g0" its sign does not matter, it vanishes on the boundary and in the result.
    boundary_normals : (n, 3) float64 array or None, read with boundary="g1" only. Rows at
        G1 boundary vertices are the prescribed unit normals (other rows are ignored); one
        whose dot product with the estimate of geofair.boundary_normals is negative is
        rejected (flipped normals or faces). None: geofair.boundary_normals(vertices, faces,
        free), the tangent plane of a least-squares quadric through the fixed vertices around
        it (error O(h²); earlier releases took the one-sided area-weighted normal, O(h)).
    polygon_ids : (m,) integer array or None: the polygon of the caller's mesh that each
        triangle was tessellated from (e.g. Blender's MeshLoopTriangle.polygon_index); an edge
        whose two triangles carry the same id is a diagonal of a polygon. None: every edge is
        an edge of the mesh. Read by inner_fairness="uniform" only (beyond the paper): its
        umbrella runs over the polygon mesh's edges, so the vertex distribution of a quad mesh
        does not depend on which diagonal split each quad. A free vertex left with fewer than
        three such neighbours (a G1 boundary vertex: with none) keeps its whole ring.
        The surface (Δ_B H, mean curvature, normals) is always that of the triangles.
    inner_fairness : where the vertices sit on the surface (section 7.3): "uniform" (regular
        vertex distribution; along the polygons' edges with polygon_ids); "conformal" (the
        discrete harmonic map with the cotangent weights of the input mesh: discrete-conformal
        to it, keeps texture distortion low; weights that obtuse triangles make negative are
        clamped to 0, and a vertex whose remaining neighbours do not surround it, at a sharp
        cone point of the input, takes the mean value weights of its ring); or
        "conformal_intrinsic" (the discrete harmonic map with the cotangent weights of the
        intrinsic Delaunay triangulation of the input, Bobenko & Springborn 2007: never
        negative, nothing clamped, so vertices land where the harmonic map puts them also on
        meshes of obtuse triangles; identical to "conformal" on a mesh that needs no intrinsic
        flip. On rough inputs (noise as large as the features) it can stall where "conformal"
        converges; see docs/ACCURACY_AND_SPEED.md, "Negative cotangent weights").
    outer_fairness : "intrinsic" (Δ_B H = 0) or "bilaplacian" (the linear Δ²f = 0 initial mesh
        of section 7.4 alone, for comparison).
    normal_weighting : free-vertex normals: "quadric" (default, beyond the paper: the tangent
        plane of a least-squares quadric through the one-ring, consistent on irregular meshes),
        "area" (the paper's choice, section 6: sum of face cross products), "angle" (Thürmer &
        Wüthrich 1998) or "max" (Max 1999, exact on spheres). Measured in docs/ACCURACY_AND_SPEED.md.
    tolerance : stop when the residual is at most this (dimensionless). The residual is
        L * max_i |Hbar_i - H_i| over the free vertices: how far the mean curvature H_i
        deviates from the cotangent-weighted mean Hbar_i = Σ_j w_ij H_j / Σ_j w_ij of its
        neighbours (the Jacobi-scaled residual of eq. (12), about h**2 |Δ_B H| for edge length
        h), with L the bounding-box diagonal of the region. Invariant under scaling, and it
        asks the same local smoothness of H on a coarse and a fine mesh (L**3 |Δ_B H| would
        ask (L/h)**2 times more of the fine one). Measured on disturbed sphere caps with Max's
        normals (the sphere is the exact discrete solution): 1e-4 leaves a max radial error of
        1e-6 (2000 free vertices) to 6e-6 (13000), below the discretization error of area
        normals there (1e-3 to 3e-4).
    max_iterations : upper bound on the iterations spent solving each level (iterations that
        the multigrid cycles of a finer level run on a coarser one are not counted), and on
        the Newton steps.
    iteration : how eq. (12) is solved; all choices solve the same discrete equations.
        "newton" (beyond the paper): Newton's method on the normal offsets of all free
        vertices at once, level by level on the progressive mesh (section 7.4's nested
        iteration; levels): the base level from the linear initial mesh, each finer level from
        the prolongation of the coarser solution, each brought to inner fairness first by
        tangential solves. Per step one inexact Newton step: GMRES on the products of the
        exact Jacobian of the defects (normals, Moreton–Séquin H and cotangent weights
        recomputed; forward differences), preconditioned by the sparse LU factorization of a
        fixed-normal Jacobian of an earlier step; steps limited to 4 mean neighbour distances
        per vertex. At convergence of the finest level tangential solves restore inner
        fairness (linearized with the turn of the tangent planes, so that repeated solves
        converge quadratically; above the base level by GMRES on a two-grid preconditioner with
        the next coarser level, three-grid with the next two, without a factorization at the
        level's size), repeated while the next one would move a vertex by more than 0.001 mean
        neighbour distances (predicted from the last move by the quadratic convergence), at
        most 8 times (the steps go on where one raised the residual). A level stops when the
        residual has not halved in 20 steps (a coarse level in 8). Where Newton's
        method fails on the base level from its linear initial mesh, the base level runs
        100 iterations of the paper's iteration and one Newton attempt from there; a
        coarse level that stops unconverged with a merit (the RMS of the scaled defects) of at
        most 0.01 still starts the next, and a coarse level above the base stops once its
        merit is at most that and a step no longer halves it. Where a coarse level fails, the hierarchy is solved
        again with other coarse weights (uniform inner fairness: from the membrane of the
        finest weights, its hierarchy decimated on the smoothed input and then on the membrane,
        then each level's own uniform weights), then the finest level alone; the membrane's
        weights go first where at least 0.55 of the free vertices have a valence
        other than 6 (an irregular connectivity), its hierarchy decimated on the membrane;
        a region solved as one level (fewer than 4 × 400 free vertices) with at least
        1400 free vertices tries two levels where the one fails.
        "paper": the local/global iteration of section 7 with multigrid cycles (levels).
        "auto" (default): "newton", and where it stops unconverged or fails, "paper" from the
        start, with Newton's method tried from the paper's iterate after 100,
        200, 400, ... iterations of the finest level (at most
        60 steps or 20 without halving the residual each); the
        first attempt that converges ends the solve (.message says after how many). The LU
        factors of the Newton steps take memory, growing faster than the vertex count; the
        README's speed table gives the steps per level and the peak memory
        (bench/speed.py).
    damping : s in q <- q~ + s t n (section 7.2), in (0, 1].
    cg_iterations : conjugate-gradient iterations of a global step (section 7.1).
    levels : levels of the progressive-mesh multigrid (section 7.4, Fig. 6), 4 times as many
        free vertices per level: 1 solves the whole region as one level; 0 (default) picks
        them from the region. For "newton": as many as keep at least 400 free vertices on the
        base level (its hierarchy coarsens the G1 boundary too, see progressive_mesh); for
        "paper": one level up to 1000 free vertices and
        about log4(free vertices / 250) + 1 above, each finer level solved by nonlinear
        multigrid cycles on the coarser ones.
    time_limit : seconds (float) the whole call may take, or None (default): automatic with
        iteration="auto", a limit on time without progress: Newton's attempts end by their own rule
        (see iteration), the paper's iteration once its residual has not halved for 5 s
        plus 0.2 ms per free vertex, and the whole call in any case after 5 times that; no limit with
        "newton" or "paper" (they run to max_iterations); float("inf") for no limit. Once spent,
        the result is returned with converged=False and a message saying so (the input
        positions if no level finished).
    progress : callable(iteration, residual) -> bool or None, called at most every 0.1 s;
        returning False stops the run early (converged is then False).
    tuning : dict or None (default): overrides of the solvers' numerical choices beyond the
        paper, from dotted names such as "newton.patience" to numbers; the names and defaults:
        geofair.defaults()["tuning"], units and valid ranges: native/include/geofair/tuning.h.
        An unknown name, a value of the wrong type or out of range raises ValueError.
    
    Returns
    -------
    FairingResult with .vertices (n', 3) float64 (n' = n unless remeshed), .faces (m', 3)
    int32, .free (n',) bool, .remeshed, .unreferenced, .origin_face and .origin_barycentric
    (see remesh; the input's faces and mask, -1 and zeros when not remeshed), .converged,
    .iterations (all levels),
    .residual, .iterations_per_level and .vertices_per_level (lists, coarsest level first),
    .iteration ("newton" or "paper"), .newton_iterations, .folds and .new_folds (edges whose
    triangles the result flips over, and those not folded in the input) and .phase_seconds
    (wall-clock seconds per phase, for profiling).
    
    Raises
    ------
    ValueError for invalid input (the message names the problem and the vertex or face; a mesh
    whose squared lengths leave the normal doubles, with a bounding-box diagonal above about
    1.3e154 or a mean edge length below about 1.5e-154, names its size), RuntimeError if the
    computation fails or diverges. NaN or Inf is never returned. Within those sizes the result
    is the same at any scale (positions are worked on in units of the mesh's own size).
    """
def fill_holes(vertices: typing.Any, faces: typing.Any, loops: typing.Any = None, *, target_edge_length: typing.Any = None, keep_outer_borders: bool = True, max_hole_edges: typing.Any = None, boundary: str = 'g1', inner_fairness: str = 'uniform', outer_fairness: str = 'intrinsic', normal_weighting: str = 'quadric', tolerance: typing.SupportsFloat | typing.SupportsIndex = 0.0001, max_iterations: typing.SupportsInt | typing.SupportsIndex = 20000, damping: typing.SupportsFloat | typing.SupportsIndex = 0.9, cg_iterations: typing.SupportsInt | typing.SupportsIndex = 10, levels: typing.SupportsInt | typing.SupportsIndex = 0, iteration: str = 'auto', progress: typing.Any = None, time_limit: typing.Any = None, tuning: typing.Any = None) -> FairingResult:
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
    target_edge_length (geofair.remesh_region), and all patches are faired together by
    geofair.fair with the new vertices free. Where that does not converge or folds an edge and
    target_edge_length is None, the holes are filled once more at half the loops' edge length
    (ragged loops need a finer fill next to them) and the better result is returned; its
    message says so.
    
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
    boundary, inner_fairness, outer_fairness, normal_weighting, tolerance, max_iterations,
    damping, cg_iterations, levels, iteration, progress, time_limit, tuning : as for
        geofair.fair (time_limit covers the filling too); boundary="g0" fills with the minimal
        surface spanned by the loop.
    
    Returns
    -------
    FairingResult: .vertices (n + k, 3), the input's n rows first and bit-identical, the k new
    vertices after; .faces (m + l, 3), the input's m faces first and unchanged, the new ones
    after, oriented like the faces around the holes; .free (n + k,) bool, True exactly at the
    new vertices; .remeshed True (.origin_face -1: a fill has no input surface); .converged,
    .residual, .message, .stop_reason, .folds, .new_folds and .phase_seconds (starting with
    "fill") as for fair.
    
    Raises
    ------
    ValueError (geofair.InvalidInputError) when loops is not a list of sequences of vertex
    indices, a loop is not a boundary loop of the mesh (the offending pair of vertices is named),
    a vertex is on two given loops, the mesh has no hole to fill (no boundary loop, or with
    loops=None every loop is left open: the message names them and why), max_hole_edges is not
    None or a positive integer, a fill would take more than 2000000 new vertices, the mesh's
    squared lengths leave the normal doubles (a bounding-box diagonal above about 1.3e154 or a
    mean edge length below about 1.5e-154: the message names the size), or for the input fair
    refuses (the message names the problem and the vertex or face); RuntimeError as fair.
    Within those sizes the fill is the same at any scale (positions are worked on in units of
    the mesh's own size).
    """
def holes_to_fill(vertices: typing.Any, faces: typing.Any, *, keep_outer_borders: bool = True, max_hole_edges: typing.Any = None) -> tuple[list, list]:
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
    spans 95 % of the area of its part's triangles (a hole less than 30 %)"). Both empty for
    a closed mesh. The same at any scale of the mesh.
    
    Raises
    ------
    ValueError as geofair.boundary_loops, for max_hole_edges not None or a positive integer,
    or a mesh whose squared lengths leave the normal doubles (see geofair.fill_holes).
    """
def intrinsic_delaunay(vertices: typing.Any, faces: typing.Any) -> tuple[typing.Annotated[numpy.typing.NDArray[numpy.int32], "[m, 3]"], typing.Annotated[numpy.typing.NDArray[numpy.float64], "[m, 3]"], int]:
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
    
    Raises ValueError for invalid input, RuntimeError if round-off made the flips cycle.
    """
def intrinsic_delaunay_laplacian(vertices: typing.Any, faces: typing.Any) -> scipy.sparse.csr_matrix:
    """
    The cotangent Laplacian of the intrinsic Delaunay triangulation (Bobenko &
    Springborn 2007) as an (n, n) scipy.sparse CSR matrix, with the conventions of
    cotangent_laplacian: L[i, j] = Σ cot of the angles opposite the intrinsic edges between
    i and j, L[i, i] = -Σ_j L[i, j]. Every off-diagonal entry is >= 0 (to round-off), unlike
    the cotangent Laplacian of a mesh with obtuse triangles; equal to cotangent_laplacian
    where the mesh is already intrinsically Delaunay.
    
    Raises ValueError for invalid input.
    """
def mean_curvature(vertices: typing.Any, faces: typing.Any, normals: typing.Any = None, normal_weighting: str = 'quadric') -> typing.Annotated[numpy.typing.NDArray[numpy.float64], "[m, 1]"]:
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
    ValueError for invalid input.
    """
def progressive_mesh(vertices: typing.Any, faces: typing.Any, free: typing.Any, levels: typing.SupportsInt | typing.SupportsIndex = 1, coarsen_boundary: bool = False) -> list[typing.Annotated[numpy.typing.NDArray[numpy.int32], "[m, 3]"]]:
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
    
    Raises ValueError for invalid input.
    """
def relax_inner_fairness(vertices: typing.Any, faces: typing.Any, free: typing.Any, normals: typing.Any, inner_fairness: str = 'uniform', tangent_planes: str = 'turning', polygon_ids: typing.Any = None) -> tuple[typing.Annotated[numpy.typing.NDArray[numpy.float64], "[m, 3]"], float]:
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
    
    Raises ValueError for invalid input, RuntimeError (geofair.SolverError) if the system is
    singular.
    """
def remesh_region(vertices: typing.Any, faces: typing.Any, free: typing.Any, *, target_edge_length: typing.Any = None, iterations: typing.SupportsInt | typing.SupportsIndex = 5) -> RemeshedRegion:
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
    ValueError for invalid input (shapes, indices, no free vertex, a free vertex on the mesh
    border, a region that is not a consistently oriented 2-manifold, invalid options).
    """
__version__: str
