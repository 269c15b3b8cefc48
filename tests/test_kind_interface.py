"""The group-kind interface, one face per layer (planmethod.kinematics.groups,
planmethod.plans.groups, planmethod.forces.groups): every registered module provides what its
layer's protocols name, and a module that lacks a function or takes other arguments — or a
kind without the face a later layer needs — is refused when that layer's registry loads,
naming the module and what is missing."""

from __future__ import annotations

from types import ModuleType

import pytest

import planmethod.forces.groups as force_groups
import planmethod.kinematics.groups as groups
import planmethod.plans.groups as plan_groups
from planmethod.forces.groups import higher as higher_forces
from planmethod.forces.groups import rrr as rrr_forces
from planmethod.forces.groups import triad as triad_forces
from planmethod.kinematics.groups import KindModule, describe, higher, registered, rrr, triad
from planmethod.plans.groups import PlanFace
from planmethod.plans.groups import higher as higher_plans
from planmethod.plans.groups import triad as triad_plans
from planmethod.vocabulary import GroupKind
from planmethod.words import render


def _copy(module: ModuleType, *, without: tuple[str, ...] = (), name: str | None = None,
          **extra) -> ModuleType:
    """A fake kind module: ``module``'s names, some left out, some added or replaced; in the
    module's own package, named ``fake_<its name>`` (or ``name``)."""
    package, _, own = module.__name__.rpartition(".")
    fake = ModuleType(f"{package}.{name or 'fake_' + own}")
    for name, value in vars(module).items():
        if not name.startswith("__") and name not in without:
            setattr(fake, name, value)
    for name, value in extra.items():
        setattr(fake, name, value)
    return fake


def test_every_registered_kind_is_described_by_its_module():
    found = {module.name: module for modules in registered().values() for module in modules}
    assert set(found) == {"rrr", "rrp", "rpr", "prp", "rpp", "triad", "higher"}
    for name in ("rrr", "rrp", "rpr", "prp", "rpp"):
        kind = found[name]
        assert isinstance(kind, KindModule) and kind.closed_form
        assert kind.kinds == (GroupKind(name.upper()),)
    assert found["rrr"].branches == 2 and found["prp"].branches == 1
    assert found["triad"].evaluate is triad.evaluate and found["triad"].priority == 10
    assert not found["higher"].closed_form and found["higher"].choose is higher.choose
    assert registered()[GroupKind.TRIAD] == (found["triad"], found["higher"])   # by priority


def test_every_kind_has_its_plans_face():
    """A dyad is drawn from its two vector equations (no face); each higher kind by its own
    module of planmethod.plans.groups — the general higher group's says it is not drawn."""
    faces = plan_groups.registered()
    assert set(faces) == {"rrr", "rrp", "rpr", "prp", "rpp", "triad", "higher"}
    assert all(faces[name] is None for name in ("rrr", "rrp", "rpr", "prp", "rpp"))
    assert faces["triad"] == PlanFace("triad", triad_plans.draw_velocity,
                                      triad_plans.draw_acceleration)
    assert faces["higher"] == PlanFace("higher", higher_plans.draw_velocity,
                                       higher_plans.draw_acceleration)


@pytest.mark.parametrize(("module", "without", "extra", "message"), [
    (rrr, ("place",), {},
     "defines neither place (ClosedFormKind) nor evaluate and choose (IterativeKind)"),
    (higher, ("choose",), {}, "defines evaluate but not choose (IterativeKind)"),
    (rrr, (), {"BRANCHES": 3}, "BRANCHES must be 1 or 2 for a closed-form kind, not 3"),
    (rrr, ("BRANCHES",), {}, "BRANCHES must be 1 or 2 for a closed-form kind, not 0"),
    (rrr, (), {"evaluate": higher.evaluate, "choose": higher.choose},
     "defines both place (ClosedFormKind) and evaluate/choose (IterativeKind)"),
    (rrr, (), {"KIND": "RRRR"}, "KIND 'RRRR' is no GroupKind"),
    (rrr, ("KIND",), {}, "defines neither KIND nor KINDS"),
    (rrr, (), {"PRIORITY": 1.5}, "PRIORITY must be a whole number, not 1.5"),
    (rrr, (), {"place": lambda: None},
     "place cannot be called with the 1 arguments of ClosedFormKind.place"),
    (triad, (), {"accepts": lambda: None},
     "accepts cannot be called with the 1 arguments of Accepts.accepts"),
    (higher, ("evaluate",), {"choose": lambda: None},   # the function there is checked too
     "defines choose but not evaluate (IterativeKind); choose cannot be called with the 2 "
     "arguments of IterativeKind.choose"),
])
def test_a_module_that_breaks_the_interface_is_refused(module, without, extra, message):
    fake = _copy(module, without=without, **extra)
    with pytest.raises(TypeError) as error:
        describe(fake)
    assert str(error.value) == f"group kind module {fake.__name__}: {message}"


def test_every_way_a_module_breaks_the_interface_is_named_at_once():
    fake = _copy(rrr, without=("KIND",), PRIORITY="high", BRANCHES=3)
    with pytest.raises(TypeError) as error:
        describe(fake)
    assert str(error.value) == (
        f"group kind module {fake.__name__}: defines neither KIND nor KINDS; BRANCHES must be "
        "1 or 2 for a closed-form kind, not 3; PRIORITY must be a whole number, not 'high'")


def test_what_a_module_leaves_out_takes_its_default():
    """Named by the last part of its module's name; without PRIORITY, 0; a kind without
    ``accepts`` takes every group of its kinds; an iterative kind has no branches of its own
    and no ``place``; a closed-form kind no ``evaluate`` or ``choose``."""
    closed = describe(_copy(rrr, without=("PRIORITY",)))
    assert (closed.name, closed.priority, closed.accepts, closed.branches) == (
        "fake_rrr", 0, None, 2)
    assert (closed.place, closed.evaluate, closed.choose) == (rrr.place, None, None)
    iterative = describe(_copy(triad))
    assert (iterative.name, iterative.branches, iterative.place) == ("fake_triad", 0, None)
    assert (iterative.evaluate, iterative.choose) == (triad.evaluate, triad.choose)
    assert iterative.accepts is triad.accepts and iterative.priority == triad.PRIORITY
    # branches are a closed-form kind's: an iterative one counts its assemblies as it finds them
    assert describe(_copy(triad, BRANCHES=2)).branches == 0


def test_a_whole_copy_is_accepted():
    """The fakes above differ from a real module by what they name alone."""
    for module in (rrr, triad, higher):
        described = describe(_copy(module))
        assert described.closed_form == (module is rrr)


def test_the_registry_checks_every_module_when_it_loads(monkeypatch):
    broken = _copy(triad, without=("choose",))
    real = groups._modules()
    monkeypatch.setattr(groups, "_REGISTRY", None)
    monkeypatch.setattr(groups, "_modules", lambda: [*real, broken])
    with pytest.raises(TypeError, match=r"fake_triad: defines evaluate but not "
                                        r"choose \(IterativeKind\)"):
        registered()
    assert groups._REGISTRY is None        # nothing half-registered
    monkeypatch.setattr(groups, "_modules", lambda: real)
    assert sorted(str(kind) for kind in registered()) == [
        "PRP", "RPP", "RPR", "RRP", "RRR", "tetrad", "triad"]


def _plan_faces(monkeypatch, kinds: list[ModuleType], faces: dict[str, ModuleType]):
    """The plans registry loaded afresh over the kinematic kind modules ``kinds`` (beside the
    real ones) and the face modules ``faces`` (beside, or instead of, the real ones)."""
    real = groups._modules()
    monkeypatch.setattr(groups, "_REGISTRY", None)
    monkeypatch.setattr(groups, "_modules", lambda: [*real, *kinds])
    modules = {**plan_groups._modules(), **faces}
    monkeypatch.setattr(plan_groups, "_REGISTRY", None)
    monkeypatch.setattr(plan_groups, "_modules", lambda: modules)
    return plan_groups.registered


@pytest.mark.parametrize(("kinds", "faces", "message"), [
    # a higher kind the kinematics knows, without its plans face
    ([_copy(triad)], {},
     "group kind module planmethod.kinematics.groups.fake_triad: no plans face "
     "(planmethod.plans.groups.fake_triad with draw_velocity and draw_acceleration: "
     "PlanDrawing); only a closed-form kind is drawn from its two vector equations"),
    # a face that lacks a function, or takes other arguments
    ([_copy(triad)], {"fake_triad": _copy(triad_plans, without=("draw_velocity",))},
     "plans face planmethod.plans.groups.fake_triad: defines draw_acceleration but not "
     "draw_velocity (PlanDrawing)"),
    ([_copy(triad)], {"fake_triad": _copy(triad_plans, draw_acceleration=lambda drawer: None)},
     "plans face planmethod.plans.groups.fake_triad: draw_acceleration cannot be called with "
     "the 2 arguments of PlanDrawing.draw_acceleration"),
    ([_copy(triad)], {"fake_triad": _copy(triad_plans, without=("draw_velocity",
                                                                 "draw_acceleration"))},
     "plans face planmethod.plans.groups.fake_triad: defines neither draw_velocity nor "
     "draw_acceleration (PlanDrawing)"),
    # a face of a dyad (drawn from its two vector equations), a face of no kind
    ([], {"rrr": _copy(triad_plans, name="rrr")},
     "plans face planmethod.plans.groups.rrr: rrr is a closed-form kind: it is drawn from its "
     "two vector equations, by no face of its own"),
    ([], {"tetrad": _copy(triad_plans, name="tetrad")},
     "plans face planmethod.plans.groups.tetrad: no group kind module "
     "planmethod.kinematics.groups.tetrad"),
])
def test_the_plans_registry_refuses_a_kind_without_its_face(monkeypatch, kinds, faces,
                                                            message):
    registered_faces = _plan_faces(monkeypatch, kinds, faces)
    with pytest.raises(TypeError) as error:
        registered_faces()
    assert str(error.value) == message
    assert plan_groups._REGISTRY is None          # nothing half-registered


def test_a_new_higher_kind_with_its_plans_face_is_drawn_by_it(monkeypatch):
    """The registries find a kind and its face by their modules alone: a copy of the triad
    with a copy of its plans face is registered in both layers."""
    kind, face = _copy(triad), _copy(triad_plans)
    faces = _plan_faces(monkeypatch, [kind], {"fake_triad": face})()
    assert faces["fake_triad"] == PlanFace("fake_triad", triad_plans.draw_velocity,
                                           triad_plans.draw_acceleration)


def test_every_kind_has_its_forces_face():
    faces = force_groups.registered()
    assert set(faces) == {"rrr", "rrp", "rpr", "prp", "rpp", "triad", "higher"}
    assert faces["rrr"] is rrr_forces.reactions and faces["triad"] is triad_forces.reactions
    assert faces["higher"] is higher_forces.reactions


def _force_faces(monkeypatch, kinds: list[ModuleType], faces: dict[str, ModuleType | None]):
    """The forces registry loaded afresh over the kinematic kind modules ``kinds`` (beside the
    real ones) and the face modules ``faces`` (beside, instead of or — None — without the real
    ones)."""
    real = groups._modules()
    monkeypatch.setattr(groups, "_REGISTRY", None)
    monkeypatch.setattr(groups, "_modules", lambda: [*real, *kinds])
    modules = {name: module for name, module in {**force_groups._modules(), **faces}.items()
               if module is not None}
    monkeypatch.setattr(force_groups, "_REGISTRY", None)
    monkeypatch.setattr(force_groups, "_modules", lambda: modules)
    return force_groups.registered


@pytest.mark.parametrize(("kinds", "faces", "message"), [
    # a kind the kinematics knows, without its forces face: a dyad's, a higher kind's
    ([], {"rrr": None},
     "group kind module planmethod.kinematics.groups.rrr: no forces face "
     "(planmethod.forces.groups.rrr with reactions: Reactions)"),
    ([_copy(triad)], {},
     "group kind module planmethod.kinematics.groups.fake_triad: no forces face "
     "(planmethod.forces.groups.fake_triad with reactions: Reactions)"),
    # a face without reactions, or whose reactions takes other arguments
    ([_copy(triad)], {"fake_triad": _copy(triad_forces, without=("reactions",))},
     "forces face planmethod.forces.groups.fake_triad: defines no reactions (Reactions)"),
    ([_copy(triad)], {"fake_triad": _copy(triad_forces, reactions=lambda solver: None)},
     "forces face planmethod.forces.groups.fake_triad: reactions cannot be called with the 2 "
     "arguments of Reactions.reactions"),
    # a face of no kind
    ([], {"tetrad": _copy(triad_forces, name="tetrad")},
     "forces face planmethod.forces.groups.tetrad: no group kind module "
     "planmethod.kinematics.groups.tetrad"),
])
def test_the_forces_registry_refuses_a_kind_without_its_face(monkeypatch, kinds, faces,
                                                             message):
    registered_faces = _force_faces(monkeypatch, kinds, faces)
    with pytest.raises(TypeError) as error:
        registered_faces()
    assert str(error.value) == message
    assert force_groups._REGISTRY is None         # nothing half-registered


def test_a_triad_solved_by_the_general_higher_face_gives_the_same_reactions(monkeypatch):
    """The general higher group's forces face solves a group's 3k equilibrium equations at
    once: given the triad (a registry whose triad face is that one), the force analysis finds
    the same reactions as the triad's textbook sequence by Assur's special point."""
    import numpy as np

    from planmethod.forces import solve_forces
    from planmethod.kinematics import solve
    from planmethod.spec import load_exercise

    motion = solve(load_exercise("exercises/conveyor_sixbar.toml").mechanism,
                   np.arange(0.0, 360.0, 30.0))
    textbook = solve_forces(motion)
    faces = _force_faces(monkeypatch, [], {"triad": _copy(higher_forces, name="triad")})()
    assert faces["triad"] is higher_forces.reactions
    linear = solve_forces(motion)
    steps = [group.steps for group in linear.groups.groups if group.kind is GroupKind.TRIAD]
    assert steps and "solved at once" in render(steps[0][0])
    assert "solved at once" not in render(next(group.steps[0] for group in
                                               textbook.groups.groups
                                               if group.kind is GroupKind.TRIAD))
    scale = max(float(np.abs(r.force).max()) for r in textbook.reactions.values())
    for key, reaction in textbook.reactions.items():
        assert np.allclose(linear.reactions[key].force, reaction.force, rtol=0,
                           atol=1e-12 * scale)
