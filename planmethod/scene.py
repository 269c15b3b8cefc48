"""What a scene asks → the minimal set of groups and stages to compute.

A scene that asks only for v_C at one angle solves only the groups on the way to C, and only
up to velocities; forces are computed only when asked.

Examples
--------
>>> from planmethod.spec import load_exercise
>>> scene = plan_scene(load_exercise("exercises/compressor_slider_crank.toml"))
>>> scene.stage, scene.links
('acceleration', ('BC',))
"""

from __future__ import annotations

from dataclasses import dataclass

from .model import FRAME, Exercise

__all__ = ["Scene", "plan_scene"]


@dataclass(frozen=True, slots=True)
class Scene:
    """The links whose groups must be solved (None: all) and the last stage needed."""

    links: tuple[str, ...] | None
    stage: str
    forces: bool


def plan_scene(exercise: Exercise) -> Scene:
    """The minimal computation for the exercise's ``[ask]`` table."""
    ask, mechanism = exercise.ask, exercise.mechanism
    if ask.everything:
        stage = "acceleration"
        return Scene(None, stage, ask.forces)
    if ask.forces:
        return Scene(None, "acceleration", True)
    links: list[str] = []
    for ref in ask.velocity + ask.acceleration + ask.curvature:
        name, _, on = ref.partition("@")
        links += [on] if on else [next(link for link in mechanism.links_with_point(name))]
        if on:
            links += list(mechanism.links_with_point(name))[:1]
    links += list(ask.omega) + list(ask.epsilon)
    for key in ask.sliding:
        slide = mechanism.slide(key)
        links += [slide.link, slide.along]
    links = [link for link in dict.fromkeys(links) if link != FRAME]
    stage = "acceleration" if (ask.acceleration or ask.epsilon or ask.curvature or ask.sliding
                               ) else "velocity"
    return Scene(tuple(links), stage, False)
