"""The blockage rules of the explicit finite-element codes at one instant, to replay a scene the way each code
would have blocked it.

Every code starts from the contact state of one cycle and turns it into *flags* on leakage-surface nodes or
faces; ventsim's own rule (``"exact"``) takes the leakage nodes within the contact tolerance of a blocker at every
instant. Two kinds of contact take part:

* **secondary nodes** ``S``: leakage nodes in contact with a blocker (within the tolerance, or inside it), the
  nodes ventsim's exact rule makes active;
* **main segments** ``M``: leakage faces that a *blocker node* touches (the leakage surface is then the main side
  of the contact and the blocker's mesh nodes are its secondary nodes): :func:`touched_faces`.

Which of them a rule flags is its ``side`` (``"secondary"``, ``"main"`` or ``"both"``: a symmetric contact);
the face fractions then follow each code's law below. How a rule is sampled in time (flags at t_k = k·Δt only,
used n cycles later) is not geometry: :mod:`cases.model.fe_sampling` does that.

References
----------
- Abaqus Analysis User's Guide, "Fluid exchange definition", contact blockage: a slave node of the leakage
  surface in node-to-face (or edge-to-edge) contact is an active blockage node; A_eb = A_e·N_c/N_e.
- OpenRadioss, ``engine/source/interfaces/int07/i7for3.F``: a secondary node with a non-zero contact force sets
  ICONTACT on itself and on the four nodes IX1..IX4 of its main segment; ``engine/source/airbag/
  get_volume_area.F90`` (and ``volum0.F``): PORO of a face += 1/4 per flagged node of a 4-node shell, 1/3 of a
  3-node shell; ``engine/source/engine/resol.F``: MONVOL0 reads ICONTACT before the cycle's contact forces reset
  and set it, i.e. the previous cycle's flags; ``engine/source/airbag/airbagb1.F``: a vent's blocked part leaks
  Bvent·PORO·A, a porous fabric's FACP·PORO·A (AC' of /LEAK/MAT; nothing with Iblockage = 1).
- LS-DYNA Keyword User's Manual, ``*AIRBAG_PARTICLE``: BLOCK = 10·M + N; N = 1 "check if airbag node is in
  contact; if yes, 1/4 (quad) or 1/3 (tri) of the segment surface will not have porosity leakage", N = 2, 3, 4
  the same without blockage of external, internal or all vents; SDFBLK scales the blockage factor down, (0, 1].
  ``*AIRBAG_CPG``: BLOCK = 1, "elements receiving contact forces are blocked: porosity and venting leakage set to
  0"; BLOCK = 4 the same except at vents. ``*MAT_FABRIC``: FVOPT 2, 4, 6, 8 leak "with blockage of venting area
  due to contact"; ELA "effective leakage area for blocked fabric" (0.1: 10 % of the blocked fabric leaks).
"""
from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from blockage.areas import active_counts, blocked_face_areas, leak_area, obstruction_area

__all__ = ["RULES", "SIDES", "default_side", "default_lag", "triangulated", "LeakTree", "touched_faces", "flagged_nodes",
           "exact_fractions", "abaqus_fractions", "radioss_fractions", "lsdyna_cpm_fractions",
           "lsdyna_cpg_fractions", "face_fractions", "face_counts", "blocked_fabric_leak_area", "blocks_exchange",
           "RuleBlockage", "rule_blockage"]

#: The rules, ventsim's own first.
RULES = ("exact", "abaqus", "radioss", "lsdyna_cpm", "lsdyna_cpg")
#: Which contact a rule flags: the leakage nodes in contact, the leakage faces touched by blocker nodes, or both.
SIDES = ("secondary", "main", "both")
_SIDE = {"exact": "secondary", "abaqus": "secondary", "radioss": "both", "lsdyna_cpm": "secondary",
         "lsdyna_cpg": "both"}


def default_side(rule: str) -> str:
    """The contact side a rule flags unless told otherwise: Radioss flags the secondary node and the nodes of its
    main segment (i7for3.F), a CPG element carries contact force either way; Abaqus and CPM the leakage nodes.

    >>> default_side("radioss"), default_side("abaqus")
    ('both', 'secondary')
    """
    return _SIDE[rule]


def default_lag(rule: str) -> int:
    """Cycles between the flags and the area that uses them unless told otherwise: Radioss's uniform-pressure
    bags read the previous cycle's ICONTACT (resol.F), 1; the others 0.

    >>> default_lag("radioss"), default_lag("abaqus")
    (1, 0)
    """
    return 1 if rule == "radioss" else 0


def triangulated(faces, face_sizes) -> tuple:
    """(triangles (t, 3) int, the face of each triangle (t,) int): a quad [a, b, c, d] is [a, b, c] and [a, c, d].

    >>> tri, owner = triangulated(np.array([[0, 1, 2, 3], [1, 4, 2, -1]]), np.array([4, 3]))
    >>> tri.tolist(), owner.tolist()
    ([[0, 1, 2], [1, 4, 2], [0, 2, 3]], [0, 1, 0])
    """
    faces = np.asarray(faces, dtype=np.int64)
    quads = np.flatnonzero(np.asarray(face_sizes) == 4)
    tri = np.concatenate([faces[:, :3], faces[quads][:, [0, 2, 3]]]) if quads.size else faces[:, :3]
    return tri, np.concatenate([np.arange(len(faces)), quads])


class LeakTree:
    """The leakage surface as a blocker of the blocker nodes (its triangles in a tree, each with its face), to find
    the main segments they touch; :meth:`refit` follows a moving surface.

    Parameters
    ----------
    vertices : (n, 3) float
        Leakage-surface nodes [m].
    faces : (m, 4) int
        Padded with -1 for triangles.
    face_sizes : (m,) int
    """

    def __init__(self, vertices, faces, face_sizes):
        from blockage.blocker import Blocker

        tri, self.owner = triangulated(faces, face_sizes)
        self.blocker, self.m = Blocker(np.asarray(vertices, dtype=float), tri), len(faces)

    def refit(self, vertices) -> None:
        self.blocker.refit(np.asarray(vertices, dtype=float))

    def segments(self, points, tolerance: float, open_depth: float = 0.0) -> np.ndarray:
        """(k,) int: the face that is the main segment of each blocker node, -1 for a node out of contact.

        A blocker node (a secondary node of the contact) is in contact when its distance to the leakage surface is
        ``<= tolerance``, or when it lies behind the surface (against the faces' pseudonormal) within
        ``open_depth`` [m]; its main segment is the face nearest to it (the face the contact pairs it with).
        """
        from blockage.sides import signed_distances

        points = np.asarray(points, dtype=float).reshape(-1, 3)
        out = np.full(len(points), -1, dtype=np.int64)
        if not len(points) or not self.m:
            return out
        reach = 2.0 * max(float(tolerance), float(open_depth)) + 1e-300  # capped beyond it: never <= the tolerance
        if not open_depth > 0.0:  # the distance alone decides: one query gives the faces too
            found = self.blocker.distances(points, cutoff=float(tolerance))
            near = np.flatnonzero(found.distances <= tolerance)
            out[near] = self.owner[found.faces[near]]
            return out
        near = np.flatnonzero(signed_distances(self.blocker, points, reach, open_depth) <= tolerance)
        if near.size:
            out[near] = self.owner[self.blocker.distances(points[near], cutoff=reach).faces]
        return out

    def touched(self, points, tolerance: float, open_depth: float = 0.0) -> np.ndarray:
        """(m,) bool: the faces that are the main segment of some blocker node in contact (:meth:`segments`)."""
        out = np.zeros(self.m, dtype=bool)
        found = self.segments(points, tolerance, open_depth)
        out[found[found >= 0]] = True
        return out


def touched_faces(vertices, faces, face_sizes, points, tolerance: float, open_depth: float = 0.0) -> np.ndarray:
    """(m,) bool: the leakage faces that are the main segment of a blocker node ``points`` (k, 3) [m] in contact
    (:meth:`LeakTree.touched`).

    >>> v = np.array([[0.0, 0, 0], [1, 0, 0], [1, 1, 0], [0, 1, 0], [2, 0, 0], [2, 1, 0]])
    >>> f, k = np.array([[0, 1, 2, 3], [1, 4, 5, 2]]), np.array([4, 4])
    >>> touched_faces(v, f, k, [[1.5, 0.5, 0.001], [0.5, 0.5, 0.1]], 0.002).tolist()
    [False, True]
    """
    return LeakTree(vertices, faces, face_sizes).touched(points, tolerance, open_depth)


def flagged_nodes(secondary, touched, faces, face_sizes, side: str) -> np.ndarray:
    """(n,) bool: the leakage nodes a rule flags: the secondary nodes in contact, the nodes of the main segments
    touched (OpenRadioss i7for3.F: ICONTACT of IX1..IX4), or both.

    >>> f, k = np.array([[0, 1, 2, 3], [1, 4, 5, 2]]), np.array([4, 4])
    >>> s = np.array([True, False, False, False, False, False])
    >>> flagged_nodes(s, np.array([False, True]), f, k, "both").astype(int).tolist()
    [1, 1, 1, 0, 1, 1]
    """
    secondary = np.asarray(secondary, dtype=bool)
    if side not in SIDES:
        raise ValueError(f"side must be one of {SIDES}, got {side!r}")
    main = np.zeros(len(secondary), dtype=bool)
    faces = np.asarray(faces, dtype=np.int64)
    for corner in range(faces.shape[1]):
        ids = faces[np.asarray(touched, dtype=bool) & (np.asarray(face_sizes) > corner), corner]
        main[ids] = True
    return {"secondary": secondary, "main": main, "both": secondary | main}[side]


def _node_share(flags, faces, face_sizes) -> np.ndarray:
    """(m,) N_c/N_e: the share of each face's nodes that are flagged."""
    return active_counts(flags, faces, face_sizes) / np.asarray(face_sizes, dtype=float)


def exact_fractions(active, faces, face_sizes) -> np.ndarray:
    """(m,) N_c/N_e of ventsim's exact rule: the active nodes at the instant itself (``docs/blockage.md``)."""
    return _node_share(active, faces, face_sizes)


def abaqus_fractions(flags, faces, face_sizes) -> np.ndarray:
    """(m,) blocked fraction N_c/N_e of each face under Abaqus/Explicit's rule.

    Abaqus Analysis User's Guide, "Fluid exchange definition": the active blockage nodes are the slave nodes of
    the leakage surface in node-to-face (or edge-to-edge) contact with the blocking surfaces in the increment;
    an element with N_e nodes, N_c of them active, is blocked over A_eb = A_e·N_c/N_e.

    >>> abaqus_fractions(np.array([True, True, False, False]), np.array([[0, 1, 2, 3]]), np.array([4])).tolist()
    [0.5]
    """
    return _node_share(flags, faces, face_sizes)


def radioss_fractions(flags, faces, face_sizes) -> np.ndarray:
    """(m,) PORO of each face under OpenRadioss's rule: 1/4 per flagged node of a 4-node shell, 1/3 of a
    3-node shell, the flags being ICONTACT of the secondary nodes with a non-zero contact force and of the four
    nodes of their main segments.

    Sources: OpenRadioss ``engine/source/interfaces/int07/i7for3.F`` (the flags) and
    ``engine/source/airbag/get_volume_area.F90`` (PORO: ``poro(ii) = poro(ii) + fourth`` per flagged node of a
    quad, ``+ third`` of a triangle). A triangle meshed as a degenerate 4-node shell (node 3 repeated) would count
    its third node twice; the leakage surfaces here store triangles as 3-node faces.

    >>> radioss_fractions(np.array([True, False, True, False, True]), np.array([[0, 1, 2, 3], [1, 4, 2, -1]]),
    ...                   np.array([4, 3])).tolist()
    [0.5, 0.6666666666666666]
    """
    return _node_share(flags, faces, face_sizes)


def lsdyna_cpm_fractions(flags, faces, face_sizes, sdfblk: float = 1.0) -> np.ndarray:
    """(m,) blocked fraction of each segment under LS-DYNA ``*AIRBAG_PARTICLE`` BLOCK = 10·M + N, N >= 1:
    1/4 (quad) or 1/3 (triangle) of the segment per airbag node in contact, scaled down by SDFBLK in (0, 1].

    Source: LS-DYNA Keyword User's Manual, ``*AIRBAG_PARTICLE``, fields BLOCK and SDFBLK.

    >>> lsdyna_cpm_fractions(np.array([True, True, False, False]), np.array([[0, 1, 2, 3]]), np.array([4]),
    ...                      0.5).tolist()
    [0.25]
    """
    if not 0.0 < sdfblk <= 1.0:
        raise ValueError(f"SDFBLK must be in (0, 1], got {sdfblk!r}")
    return sdfblk * _node_share(flags, faces, face_sizes)


def lsdyna_cpg_fractions(flags, faces, face_sizes) -> np.ndarray:
    """(m,) 1 for every element that receives contact force, else 0: LS-DYNA ``*AIRBAG_CPG`` BLOCK = 1 (or 4)
    sets the porosity and venting leakage of such an element to zero.

    An element receives contact force through its nodes: it is blocked whole when one of its nodes is flagged
    (a secondary node in contact, or a node of a main segment touched, :func:`flagged_nodes`).
    Source: LS-DYNA Keyword User's Manual, ``*AIRBAG_CPG``, field BLOCK.

    >>> lsdyna_cpg_fractions(np.array([True, False, False, False, False]),
    ...                      np.array([[0, 1, 2, 3], [1, 4, 2, -1]]), np.array([4, 3])).tolist()
    [1.0, 0.0]
    """
    return (active_counts(flags, faces, face_sizes) > 0).astype(float)


def face_counts(rule: str, flags, faces, face_sizes) -> np.ndarray:
    """(m,) int: the blocked share of each face in nodes, N_c of the face (N_e when the rule blocks it whole):
    the face's blocked fraction before SDFBLK is counts / N_e."""
    counts = active_counts(flags, faces, face_sizes)
    return np.where(counts > 0, np.asarray(face_sizes), 0) if rule == "lsdyna_cpg" else counts


def face_fractions(rule: str, flags, faces, face_sizes, sdfblk: float = 1.0) -> np.ndarray:
    """(m,) the blocked fraction of each face under ``rule`` (one of :data:`RULES`) from the flagged nodes."""
    law = {"exact": exact_fractions, "abaqus": abaqus_fractions, "radioss": radioss_fractions,
           "lsdyna_cpg": lsdyna_cpg_fractions}
    if rule == "lsdyna_cpm":
        return lsdyna_cpm_fractions(flags, faces, face_sizes, sdfblk)
    if rule not in law:
        raise ValueError(f"rule must be one of {RULES}, got {rule!r}")
    return law[rule](flags, faces, face_sizes)


def blocked_fabric_leak_area(total_area: float, obstruction: float, leak_fraction: float) -> float:
    """Leakage area [m^2] of a fabric whose blocked part still leaks a fraction ``leak_fraction`` of its area.

    .. math::  A = (A_{total} - A_{obstr}) + f\\,A_{obstr}

    LS-DYNA ``*MAT_FABRIC`` ELA ("effective leakage area for blocked fabric": 0.1, 10 % of the blocked fabric
    leaks; 0 by default); Radioss ``/LEAK/MAT`` AC' (airbagb1.F: the blocked part leaks FACP·PORO·A, the free part
    (1 − PORO)·A). It is the permeability of :func:`blockage.areas.leak_area`.

    >>> blocked_fabric_leak_area(2.0, 0.5, 0.1)
    1.55
    """
    return leak_area(total_area, obstruction, permeability=leak_fraction)


def blocks_exchange(rule: str, block: int, vent: bool, external: bool) -> bool:
    """Whether ``rule`` blocks an exchange at all: a vent (``vent``: an orifice) to the ambient (``external``) or
    to another cavity, or a porous fabric.

    LS-DYNA ``*AIRBAG_PARTICLE`` BLOCK = 10·M + N: N = 0 no blockage; 1 blockage everywhere; 2 no blockage of
    external vents; 3 of internal vents; 4 of any vent (M, the treatment of particles escaping through deleted
    elements, has no bearing here). ``*AIRBAG_CPG`` BLOCK: 0 off, 1 on, 4 on except at vents. The other rules
    block every blocked exchange.

    >>> blocks_exchange("lsdyna_cpm", 12, vent=True, external=True), blocks_exchange("lsdyna_cpm", 12, True, False)
    (False, True)
    """
    if rule not in ("lsdyna_cpm", "lsdyna_cpg"):
        return True
    n = block % 10
    if n == 0:
        return False
    return not vent or n == 1 or (n == 2 and not external) or (n == 3 and external)


@dataclass(frozen=True)
class RuleBlockage:
    """One rule at one instant: ``flags`` (n,) bool, ``fractions`` (m,) blocked fraction of each face,
    ``face_blocked_area`` (m,) [m^2], ``obstruction_area`` and ``leak_area`` [m^2]."""

    flags: np.ndarray
    fractions: np.ndarray
    face_blocked_area: np.ndarray
    obstruction_area: float
    leak_area: float


def rule_blockage(rule: str, leak, blockers, tolerance: float, *, side: str | None = None, sdfblk: float = 1.0,
                  leak_fraction: float = 0.0, open_depth: float = 0.0) -> RuleBlockage:
    """The blockage of a leakage surface under ``rule`` at one pose (no time sampling, no lag).

    Parameters
    ----------
    rule : str
        One of :data:`RULES`.
    leak : blockage.LeakageSurface
    blockers : list of trimesh.Trimesh
        The blocking surfaces where they are (their vertices are the blocker nodes).
    tolerance : float
        Contact tolerance [m].
    side : str, optional
        :data:`SIDES`; default :func:`default_side`.
    sdfblk : float
        ``lsdyna_cpm``: SDFBLK.
    leak_fraction : float
        Fraction of the blocked area that still leaks (ELA, AC', Bvent).
    open_depth : float
        Depth [m] behind the leakage surface (or an open blocker) that counts as contact.
    """
    from blockage.api import evaluate

    side = side or default_side(rule)
    secondary = evaluate(leak, blockers, tolerance, penetration=open_depth or True).active_nodes
    touched = np.zeros(len(leak.faces), dtype=bool)
    if side != "secondary":
        for mesh in blockers:
            touched |= touched_faces(leak.vertices, leak.faces, leak.face_sizes, np.asarray(mesh.vertices), tolerance,
                                     open_depth)
    flags = flagged_nodes(secondary, touched, leak.faces, leak.face_sizes, side)
    fractions = face_fractions(rule, flags, leak.faces, leak.face_sizes, sdfblk)
    blocked = blocked_face_areas(leak.face_areas, fractions, np.ones(len(fractions)))
    obstruction = obstruction_area(blocked)
    return RuleBlockage(flags, fractions, blocked, obstruction,
                        blocked_fabric_leak_area(leak.total_area, obstruction, leak_fraction))
