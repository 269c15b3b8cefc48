"""Structural analysis: mobility W = 3n − 2p5 − p4 and the decomposition into Assur groups.

The course writes Chebyshev's formula with p4, the higher pairs (cam, gear teeth: one freedom
taken each), beside p5, the lower pairs (two taken each). The model has lower pairs only —
revolute and prismatic (:class:`~planmethod.vocabulary.PairKind`) — so p4 is 0 by construction:
:attr:`Structure.p4` says so, and the formula and the report still print it.

The decomposition starts from the frame and the drive link and repeatedly detaches the smallest
set of still-unknown links that is attached to known links only and has 3k = 2p (a dyad: two
links, three pairs; a triad: four links, six pairs), in build order. A dyad's kind is read from
its pairs in order external–internal–external: RRR (type 1), RRP (2), RPR (3), PRP (4), RPP (5).

Examples
--------
>>> from planmethod.spec import parse_exercise
>>> from pathlib import Path
>>> exercise = parse_exercise(Path("exercises/compressor_slider_crank.toml").read_text())
>>> structure = analyse_structure(exercise.mechanism)
>>> (structure.n, structure.p5, structure.mobility)
(3, 4, 1)
>>> [(str(g.kind), g.links, g.group_class, g.order) for g in structure.groups]
[('RRP', ('BC', 'slider'), 2, 2)]
"""

from __future__ import annotations

from collections.abc import Iterable, Mapping
from dataclasses import dataclass
from itertools import combinations

from .errors import StructureError
from .model import FRAME, Mechanism, Slide
from .vocabulary import GroupKind, PairKind, group_kind_words, point_text
from .words.message import Message, message
from .words.render import render

__all__ = ["AssurGroup", "Joint", "Structure", "analyse_structure", "describe",
           "structure_words"]


@dataclass(frozen=True, slots=True)
class Joint:
    """A kinematic pair as a group sees it.

    For a revolute pair ``point`` is the shared point and ``links`` the two links it joins (the
    group's link first for an external pair). For a prismatic pair ``slide`` is the
    :class:`~planmethod.model.Slide` and ``links`` is (slide.link, slide.along).
    """

    kind: PairKind
    point: str
    links: tuple[str, str]
    slide: Slide | None = None

    def other(self, link: str) -> str:
        """The link on the other side of the pair from ``link``."""
        return self.links[1] if self.links[0] == link else self.links[0]

    @property
    def label(self) -> str:
        return self.slide.key if self.slide is not None else self.point


@dataclass(frozen=True, slots=True)
class AssurGroup:
    """An Assur group in build order.

    For a dyad ``links`` is (L1, L2) and ``joints`` is (external of L1, internal, external of L2);
    ``kind`` is one of RRR, RRP, RPR, PRP, RPP. For a class III or IV group ``kind`` is
    ``triad`` or ``tetrad``, ``joints`` lists internal then external pairs.
    """

    index: int
    kind: GroupKind
    links: tuple[str, ...]
    joints: tuple[Joint, ...]
    group_class: int
    order: int
    attached_to: tuple[str, ...]

    @property
    def type_number(self) -> int | None:
        """The dyad's type (1–5) in the Russian school's numbering, None for other groups."""
        return self.kind.type_number

    @property
    def name(self) -> str:
        return "+".join(self.links)

    @property
    def is_dyad(self) -> bool:
        return self.kind.is_dyad


@dataclass(frozen=True, slots=True)
class Structure:
    """Mobility counts and the Assur groups in build order."""

    n: int
    p5: int
    mobility: int
    driver: str
    groups: tuple[AssurGroup, ...]

    @property
    def p4(self) -> int:
        """The higher pairs: none, the model has lower pairs only (see the module docstring)."""
        return 0

    def group_of(self, link: str) -> AssurGroup | None:
        """The group that solves ``link`` (None for the frame and the drive link)."""
        for group in self.groups:
            if link in group.links:
                return group
        return None

    def groups_needed(self, links: Iterable[str]) -> tuple[AssurGroup, ...]:
        """The groups on the way to ``links``: each link's group and the groups it rests on,
        in build order."""
        needed: set[int] = set()
        stack = [link for link in links]
        while stack:
            group = self.group_of(stack.pop())
            if group is None or group.index in needed:
                continue
            needed.add(group.index)
            stack.extend(group.attached_to)
        return tuple(group for group in self.groups if group.index in needed)


def _group_pairs(mechanism: Mechanism, group: tuple[str, ...], known: set[str]):
    """Pairs of ``group`` with itself (internal) and with known links (external)."""
    internal: list[Joint] = []
    external: list[Joint] = []
    for pair in mechanism.revolutes:
        inside = [link for link in pair.links if link in group]
        if not inside:
            continue
        known_side = [link for link in pair.links if link in known]
        if known_side:
            for link in inside:
                external.append(Joint(PairKind.REVOLUTE, pair.point, (link, known_side[0])))
        else:
            for link in inside[1:]:
                internal.append(Joint(PairKind.REVOLUTE, pair.point, (inside[0], link)))
    for pair in mechanism.slides:
        ends = (pair.link, pair.along)
        inside = [link for link in ends if link in group]
        if len(inside) == 2:
            internal.append(Joint(PairKind.PRISMATIC, pair.point, ends, pair))
        elif len(inside) == 1 and any(link in known for link in ends):
            external.append(Joint(PairKind.PRISMATIC, pair.point, ends, pair))
    return internal, external


def _connected(links: tuple[str, ...], internal: list[Joint]) -> bool:
    reached = {links[0]}
    changed = True
    while changed:
        changed = False
        for joint in internal:
            a, b = joint.links
            if (a in reached) != (b in reached):
                reached |= {a, b}
                changed = True
    return reached >= set(links)


def _dyad(index: int, links: tuple[str, str], internal, external) -> AssurGroup | None:
    if len(internal) != 1 or len(external) != 2:
        return None
    first, second = links
    ext = {link: [j for j in external if first_link(j, links) == link] for link in links}
    if len(ext[first]) != 1 or len(ext[second]) != 1:
        return None
    joints = (ext[first][0], internal[0], ext[second][0])
    pattern = "".join(j.kind for j in joints)
    if pattern == "PPP":
        raise StructureError(
            message("a dyad of three prismatic pairs (PPP) has no definite position"),
            link=f"{first}, {second}")
    kind = GroupKind.of_dyad(pattern)
    if kind is None:  # read the other way round (PPR is an RPP, PRR an RRP)
        joints = joints[::-1]
        links = (second, first)
        kind = GroupKind.of_dyad("".join(j.kind for j in joints))
    if kind is GroupKind.RPR and joints[1].slide.link != links[0]:
        # the block (the prismatic pair's `link`) first: X is then its pin taken on the guide
        joints, links = joints[::-1], links[::-1]
    attached = tuple(dict.fromkeys(j.other(first_link(j, links)) for j in (joints[0], joints[2])))
    return AssurGroup(index, kind, links, joints, 2, 2, attached)


def first_link(joint: Joint, group: tuple[str, ...]) -> str:
    """The group link that an external ``joint`` belongs to."""
    return joint.links[0] if joint.links[0] in group else joint.links[1]


def _larger(index: int, links: tuple[str, ...], internal, external) -> AssurGroup | None:
    degree = {link: 0 for link in links}
    for joint in internal:
        for link in joint.links:
            degree[link] += 1
    attached = tuple(dict.fromkeys(j.other(first_link(j, links)) for j in external))
    if len(links) == 4 and len(internal) == 3 and max(degree.values()) == 3:
        central = max(degree, key=degree.get)
        ordered = (central, *[link for link in links if link != central])
        return AssurGroup(index, GroupKind.TRIAD, ordered, tuple(internal) + tuple(external),
                          3, len(external), attached)
    if len(links) == 4 and len(internal) == 4 and set(degree.values()) == {2}:
        return AssurGroup(index, GroupKind.TETRAD, links, tuple(internal) + tuple(external), 4,
                          len(external), attached)
    return None


def analyse_structure(mechanism: Mechanism) -> Structure:
    """Count the mobility and decompose the mechanism into Assur groups.

    Parameters
    ----------
    mechanism
        The mechanism to analyse.

    Raises
    ------
    StructureError
        If W ≠ 1, or the links that remain cannot be split into supported Assur groups.
    """
    moving = mechanism.moving_links
    n = len(moving)
    p5 = sum(len(pair.links) - 1 for pair in mechanism.revolutes) + len(mechanism.slides)
    p4 = 0   # the model has no higher pairs (see the module docstring)
    mobility = 3 * n - 2 * p5 - p4
    if mobility != 1:
        raise _mobility_error(mechanism, n, p5, p4, mobility)
    driver = mechanism.drive.link
    known = {FRAME, driver}
    remaining = [link for link in moving if link != driver]
    groups: list[AssurGroup] = []
    while remaining:
        found = _next_group(mechanism, remaining, known, len(groups))
        if found is None:
            raise StructureError(
                message("these links do not form supported Assur groups (dyads or class III "
                        "triads) attached to the frame and the drive link"),
                link=", ".join(remaining))
        groups.append(found)
        known |= set(found.links)
        remaining = [link for link in remaining if link not in found.links]
    return Structure(n, p5, mobility, driver, tuple(groups))


def _next_group(mechanism: Mechanism, remaining: list[str], known: set[str],
                index: int) -> AssurGroup | None:
    """The smallest set of the ``remaining`` links attached to ``known`` links only with
    3k = 2p (a dyad, else a class III or IV group), in build order; None if there is none."""
    for size in (2, 4):
        for subset in combinations(remaining, size):
            internal, external = _group_pairs(mechanism, subset, known)
            if 3 * size != 2 * (len(internal) + len(external)):
                continue
            if not _connected(subset, internal):
                continue
            found = (_dyad if size == 2 else _larger)(index, subset, internal, external)
            if found:
                return found
    return None


def _mobility_error(mechanism: Mechanism, n: int, p5: int, p4: int,
                    mobility: int) -> StructureError:
    """W ≠ 1, with the counts, what it means, and the links and points that look loose."""
    moving = mechanism.moving_links
    hint = (message("it has too many freedoms: some link is not held") if mobility > 1 else
            message("it is locked (a structure, not a mechanism)"))
    loose = [link for link in moving
             if sum(link in pair.links for pair in mechanism.revolutes)
             + sum(link in (s.link, s.along) for s in mechanism.slides) < 2]
    lonely = [f"{point} ({link})" for link in loose
              for point in mechanism.links[link].points
              if len(mechanism.links_with_point(point)) == 1]
    return StructureError(message(
        "W = 3n − 2p5 − p4 = 3·{n} − 2·{p5} − {p4} = {mobility}, expected 1: {hint}{loose}"
        "{lonely}", n=n, p5=p5, p4=p4, mobility=mobility, hint=hint,
        loose=message(" (links with fewer than two pairs: {links})", links=loose) if loose
        else "",
        lonely=message("; points named in one link only: {points} — a revolute pair needs "
                       "its point named in both links", points=lonely) if lonely else ""),
        link=", ".join(moving))


def structure_words(structure: Structure, numbers: Mapping[str, int] | None = None
                    ) -> tuple[Message, ...]:
    """The structural analysis as a course prints it, line by line (see :func:`describe`).

    Examples
    --------
    >>> [render(line) for line in structure_words(Structure(3, 4, 1, "AB", ()))][1]
    'drive link AB with the frame: class I mechanism'
    """
    numbered = bool(numbers) and all(link in numbers for link in (FRAME, structure.driver))
    lines = [message("n = {n}, p5 = {p5}, p4 = {p4}, W = 3n − 2p5 − p4 = 3·{n} − 2·{p5} − "
                     "{p4} = {mobility}", n=structure.n, p5=structure.p5, p4=structure.p4,
                     mobility=structure.mobility),
             message("drive link {number} ({name}) with the frame {frame}: class I mechanism",
                     number=numbers[structure.driver], name=structure.driver.replace("_", " "),
                     frame=numbers[FRAME]) if numbered else
             message("drive link {link} with the frame: class I mechanism",
                     link=structure.driver)]
    lines += [_group_words(group, numbers if numbered else None) for group in structure.groups]
    if structure.groups:
        lines.append(message("the mechanism is of class {number}", number=max(
            [group.group_class for group in structure.groups] + [1])))
    return tuple(lines)


def _group_words(group: AssurGroup, numbers: Mapping[str, int] | None) -> Message:
    """One Assur group's line: its links, kind, class and order, pairs, and what it is
    attached to (the links by their numbers where ``numbers`` has every one)."""
    kind = (message("{kind} (type {number})", kind=group.kind.value, number=group.type_number)
            if group.is_dyad else group_kind_words(group.kind))
    if not (numbers and all(link in numbers for link in group.links + group.attached_to)):
        return message("group {index}: links {links} — {kind}, class {group_class}, order "
                       "{order}; pairs {pairs}; attached to {attached}", index=group.index + 1,
                       links=list(group.links), kind=kind, group_class=group.group_class,
                       order=group.order, pairs=[joint.label for joint in group.joints],
                       attached=list(group.attached_to))
    pairs = [point_text(joint.point) if joint.slide is None else
             f"{numbers[joint.slide.link]}–{numbers[joint.slide.along]}"
             for joint in group.joints]
    links = sorted(group.links, key=numbers.__getitem__)
    fields = dict(index=group.index + 1, numbers=[numbers[link] for link in links],
                  names=[link.replace("_", " ") for link in links], kind=kind,
                  group_class=group.group_class, order=group.order, pairs=pairs,
                  attached=[numbers[link] for link in group.attached_to])
    if len(group.attached_to) == 1:
        return message("group {index}: links {numbers} ({names}) — {kind}, class {group_class}, "
                       "order {order}; pairs {pairs}; attached to link {attached}", **fields)
    return message("group {index}: links {numbers} ({names}) — {kind}, class {group_class}, "
                   "order {order}; pairs {pairs}; attached to links {attached}", **fields)


def describe(structure: Structure, numbers: Mapping[str, int] | None = None) -> str:
    """The structural analysis as a course prints it (:func:`structure_words`, as text in
    the language spoken now).

    Parameters
    ----------
    structure
        What :func:`analyse_structure` returned.
    numbers
        The links' numbers in the course's notation
        (:func:`planmethod.numbering.course_numbers`): links are then named by number (links
        2, 3 (BC, slider)), a prismatic pair by its two links (3–0); without them, by name.

    Examples
    --------
    >>> print(describe(Structure(3, 4, 1, "AB", ())))  # doctest: +NORMALIZE_WHITESPACE
    n = 3, p5 = 4, p4 = 0, W = 3n − 2p5 − p4 = 3·3 − 2·4 − 0 = 1
    drive link AB with the frame: class I mechanism
    >>> print(describe(Structure(3, 4, 1, "AB", ()), {"frame": 0, "AB": 1}).splitlines()[1])
    drive link 1 (AB) with the frame 0: class I mechanism
    """
    return "\n".join(render(line) for line in structure_words(structure, numbers))
