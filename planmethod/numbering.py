"""The links of a mechanism numbered as its course numbers them (docs/notation.md).

A course numbers the frame 0, the crank 1 and then the moving links in the order their Assur
groups attach — group by group in build order, each group's links in the order the exercise
lists them — as both papers the project reproduces do: the compressor's connecting rod BC is
link 2 (ω₂, ε₂), its slider 3, the reactions R₀₁, R₁₂, R₂₃, R₀₃. An exercise's ``[notation]``
table chooses another convention (:class:`planmethod.model.Notation`): the frame last (the
compressor paper's "post 4") or first as 1 (the crank 2, as English-language texts write θ₂,
ω₂), and explicit numbers. Every printed symbol takes its subscript from here; the drive's
symbols (φ, ω, ε of the crank) follow the crank's number.

Examples
--------
>>> from planmethod.spec import load_exercise
>>> course_numbers(load_exercise("exercises/compressor_slider_crank.toml").mechanism)
{'frame': 0, 'AB': 1, 'BC': 2, 'slider': 3}
>>> course_numbers(load_exercise("exercises/conveyor_sixbar.toml").mechanism)
{'frame': 0, 'crank': 1, 'rod': 2, 'tray': 3, 'rocker_EF': 4, 'rocker_DG': 5}
"""

from __future__ import annotations

import functools

from .errors import StructureError
from .model import FRAME, Mechanism
from .structure import analyse_structure
from .vocabulary import link_numbers, numbered

__all__ = ["attach_order", "course_numbers", "course_symbols"]


def attach_order(mechanism: Mechanism) -> list[str]:
    """The moving links in the order a course numbers them: the crank, then each Assur
    group's links (in the exercise's order) as the groups attach. A mechanism whose
    structure cannot be analysed keeps the exercise's order.

    >>> from planmethod.spec import load_exercise
    >>> attach_order(load_exercise("exercises/shaper_sixbar.toml").mechanism)
    ['crank', 'block', 'lever', 'rod', 'ram']
    """
    try:
        groups = analyse_structure(mechanism).groups
    except StructureError:
        return [mechanism.drive.link] + [link for link in mechanism.moving_links
                                         if link != mechanism.drive.link]
    listed = {link: index for index, link in enumerate(mechanism.links)}
    order = [mechanism.drive.link]
    for group in groups:
        order += sorted(group.links, key=listed.__getitem__)
    return order + [link for link in mechanism.moving_links if link not in order]


@functools.lru_cache(maxsize=256)
def _numbers(mechanism: Mechanism) -> tuple[tuple[str, int], ...]:
    notation = mechanism.notation
    return tuple(link_numbers(attach_order(mechanism), mechanism.drive.link, FRAME,
                              frame_place=notation.frame, explicit=notation.numbers).items())


def course_numbers(mechanism: Mechanism) -> dict[str, int]:
    """Each link's number under the mechanism's notation, in the order of the numbers.

    Parameters
    ----------
    mechanism
        The mechanism; its ``notation`` (the exercise's ``[notation]`` table) chooses the
        convention: by default the frame 0, the crank 1, the other links 2, 3, … in the order
        their Assur groups attach.

    Returns
    -------
    dict
        Link name → number.

    Examples
    --------
    >>> from planmethod.spec import load_exercise
    >>> course_numbers(load_exercise("exercises/compressor_slider_crank.toml").mechanism)
    {'frame': 0, 'AB': 1, 'BC': 2, 'slider': 3}
    """
    return dict(_numbers(mechanism))


def course_symbols(mechanism: Mechanism) -> dict[str, str]:
    """The symbols a task's text quotes by name (``{symbol.omega}`` in a template's
    description), in the mechanism's notation: the crank's ``phi``, ``omega`` and ``epsilon``
    (φ₁, ω₁, ε₁ by default, φ₂ … where the frame is 1) and each moving link's ``omega_L`` and
    ``epsilon_L``.

    Parameters
    ----------
    mechanism
        The mechanism; its ``notation`` chooses the numbering (:func:`course_numbers`).

    Returns
    -------
    dict
        Name → symbol as printed.

    Examples
    --------
    >>> from planmethod.spec import load_exercise
    >>> symbols = course_symbols(load_exercise("exercises/compressor_slider_crank.toml").mechanism)
    >>> symbols["phi"], symbols["omega"], symbols["omega_BC"], symbols["epsilon_BC"]
    ('φ₁', 'ω₁', 'ω₂', 'ε₂')
    """
    numbers = course_numbers(mechanism)
    crank = numbers[mechanism.drive.link]
    out = {"phi": numbered("φ", crank), "omega": numbered("ω", crank),
           "epsilon": numbered("ε", crank)}
    for link, number in numbers.items():
        if link != FRAME:
            out[f"omega_{link}"] = numbered("ω", number)
            out[f"epsilon_{link}"] = numbered("ε", number)
    return out
