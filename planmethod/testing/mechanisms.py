"""The reference mechanisms of the tests, as exercise dicts (the tables of an exercise file).

Each function returns a fresh dict, with keyword arguments for the lengths, the drive and the
guides; :func:`planmethod.spec.exercise_from_dict` turns it into an exercise.

Examples
--------
>>> from planmethod.spec import exercise_from_dict
>>> mechanism = exercise_from_dict(slider_crank(offset=0.01)).mechanism
>>> mechanism.links["frame"].points["G"]
(0.0, -0.01)
>>> with_changes(fourbar(), title="another")["title"]
'another'
"""

from __future__ import annotations

import copy

__all__ = [
    "fourbar",
    "scotch_yoke",
    "shaper",
    "slider_crank",
    "slotted_lever",
    "two_guides",
    "with_changes",
]


def fourbar(*, ground=0.30, crank=0.08, coupler=0.22, rocker=0.18, angle=60.0,
            omega=10.0, epsilon=0.0, point=(0.10, 0.05)) -> dict:
    """Reference case A (defaults; docs/reference-cases.md): a crank-rocker with coupler point P."""
    return {
        "title": "four-bar",
        "drive": {"link": "AB", "pivot": "A", "angle": angle, "omega": omega,
                  "epsilon": epsilon},
        "links": {"frame": {"A": [0, 0], "D": [ground, 0]}, "AB": {"A": [0, 0], "B": [crank, 0]},
                  "BC": {"B": [0, 0], "C": [coupler, 0], "P": list(point)},
                  "CD": {"C": [0, 0], "D": [rocker, 0]}},
        "sketch": {"C": [ground * 0.8, rocker]},
    }


def slider_crank(*, crank=0.06, rod=0.18, offset=0.0, angle=45.0, omega=100.0,
                 epsilon=0.0) -> dict:
    """The compressor slider-crank of Abduvaliev & Abduxoshimov (defaults), optionally with the
    guide ``offset`` below A."""
    return {
        "title": "slider-crank",
        "drive": {"link": "AB", "pivot": "A", "angle": angle, "omega": omega,
                  "epsilon": epsilon},
        "links": {"frame": {"A": [0, 0], "G": [0, -offset]}, "AB": {"A": [0, 0], "B": [crank, 0]},
                  "BC": {"B": [0, 0], "C": [rod, 0], "D": [rod / 2, 0]},
                  "slider": {"C": [0, 0]}},
        "slide": [{"link": "slider", "along": "frame", "through": "G", "direction": 0}],
        "sketch": {"C": [crank + rod, -offset]},
    }


def slotted_lever(*, crank=0.10, centres=0.30, angle=30.0, omega=10.0, epsilon=0.0) -> dict:
    """Reference case C (defaults; docs/reference-cases.md): an RPR dyad with the Coriolis
    component."""
    return {
        "title": "slotted lever",
        "drive": {"link": "crank", "pivot": "O1", "angle": angle, "omega": omega,
                  "epsilon": epsilon},
        "links": {"frame": {"O1": [0, 0], "O2": [0, -centres]},
                  "crank": {"O1": [0, 0], "B": [crank, 0]}, "block": {"B": [0, 0]},
                  "lever": {"O2": [0, 0], "C": [1.5 * (crank + centres), 0.0]}},
        "slide": [{"link": "block", "along": "lever", "through": "O2", "direction": 0}],
    }


def scotch_yoke(*, crank=0.10, angle=30.0, omega=10.0, epsilon=-4.0, slot=80.0,
                guide=10.0) -> dict:
    """An RPP dyad: block on the crank pin, sliding in a yoke that slides in the frame."""
    return {
        "title": "scotch yoke",
        "drive": {"link": "crank", "pivot": "O", "angle": angle, "omega": omega,
                  "epsilon": epsilon},
        "links": {"frame": {"O": [0, 0], "G": [0, 0.5]}, "crank": {"O": [0, 0], "B": [crank, 0]},
                  "block": {"B": [0, 0]}, "yoke": {"Y": [0, 0], "Z": [0.2, 0.1]}},
        "slide": [{"link": "block", "along": "yoke", "through": "Y", "direction": slot},
                  {"link": "yoke", "along": "frame", "through": "G", "direction": guide,
                   "point": "Y"}],
    }


def two_guides(*, angle=30.0, omega=10.0, epsilon=2.0) -> dict:
    """A PRP dyad: a block slides on a guide carried by the crank and is pinned to a slider on
    a fixed guide."""
    return {
        "title": "two guides",
        "drive": {"link": "crank", "pivot": "O", "angle": angle, "omega": omega,
                  "epsilon": epsilon},
        "links": {"frame": {"O": [0, 0], "G": [0, 0.5]},
                  "crank": {"O": [0, 0], "B": [0.1, 0], "H": [0.3, 0.05]},
                  "s1": {"Q": [0, 0]}, "s2": {"Q": [0, 0]}},
        "slide": [{"link": "s1", "along": "crank", "through": "H", "direction": 70},
                  {"link": "s2", "along": "frame", "through": "G", "direction": 10}],
    }


def shaper(*, angle=60.0, omega=8.0) -> dict:
    """The shaper six-bar of ``exercises/shaper_sixbar.toml``: RPR then RRP in series."""
    return {
        "title": "shaper",
        "drive": {"link": "crank", "pivot": "O1", "angle": angle, "omega": omega},
        "links": {"frame": {"O1": [0, 0.30], "O2": [0, 0], "E": [0, 0.62]},
                  "crank": {"O1": [0, 0], "B": [0.10, 0]}, "block": {"B": [0, 0]},
                  "lever": {"O2": [0, 0], "C": [0.60, 0]}, "rod": {"C": [0, 0], "D": [0.25, 0]},
                  "ram": {"D": [0, 0]}},
        "slide": [{"link": "block", "along": "lever", "through": "O2", "direction": 0},
                  {"link": "ram", "along": "frame", "through": "E", "direction": 0}],
        "sketch": {"C": [0.10, 0.59], "D": [0.33, 0.62]},
    }


def with_changes(data: dict, **top) -> dict:
    """A deep copy of an exercise dict with top-level tables replaced."""
    out = copy.deepcopy(data)
    out.update(top)
    return out
