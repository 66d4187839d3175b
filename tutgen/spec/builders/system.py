"""The spec -> model step in one place: every section builder, called in turn, and the model they make.

Each top-level key of a spec has one builder (a module of this package); they share one
:class:`~tutgen.spec.builders.context.Context`, which holds the names declared so far and collects every
problem. :func:`build_system` is the only place that knows the order: a section is built after the
sections whose names it may use.
"""

from __future__ import annotations

import dataclasses
from typing import Any

from tutgen.errors import SpecErrors
from tutgen.model.system import System
from tutgen.spec import schema as S
from tutgen.spec.builders.analysis import build_analysis
from tutgen.spec.builders.arm import build_arm
from tutgen.spec.builders.ask import build_ask
from tutgen.spec.builders.bodies import build_bodies, declared_bodies
from tutgen.spec.builders.constraints import build_constraints, build_independent_coordinates
from tutgen.spec.builders.context import Context
from tutgen.spec.builders.conventions import build_conventions
from tutgen.spec.builders.coordinates import build_coordinates, check_prescribed, coordinates_with_dimensions
from tutgen.spec.builders.elements import build_elements
from tutgen.spec.builders.energy import build_energy
from tutgen.spec.builders.figure import build_figure
from tutgen.spec.builders.given import build_given
from tutgen.spec.builders.gravity import build_gravity
from tutgen.spec.builders.joints import build_joints, check_explicit_placement
from tutgen.spec.builders.loads import build_generalized_forces, build_loads
from tutgen.spec.builders.loops import build_loop_joints
from tutgen.spec.builders.marking import build_marking
from tutgen.spec.builders.methods import build_methods
from tutgen.spec.builders.parameters import build_parameters
from tutgen.spec.builders.simulate import build_simulate
from tutgen.spec.builders.texts import build_question_title, build_statement, build_texts, build_title
from tutgen.spec.loader import KeyPath, SourceMap
from tutgen.spec.richtext import with_texts


def build_system(doc: S.SpecDoc, data: dict[str, Any], smap: SourceMap, dropped: set[KeyPath]) -> System:
    """Check names, expressions, units and cross-references of a spec whose shape is right; build the model.

    ``data`` is the spec as loaded (how it was written), ``dropped`` the parts of it set aside for shape
    errors, already reported. Raises :class:`SpecErrors` with every problem found.
    """
    ctx = Context(doc, data, smap, set(dropped))
    # The sections, in order. Parameters and coordinates come first: every expression may use their
    # names. A new top-level spec key is one builder module and one line here, after the sections
    # whose names it uses.
    parameters = build_parameters(ctx)
    build_coordinates(ctx)
    title = build_title(ctx)
    statement = build_statement(ctx)
    question_title = build_question_title(ctx)
    given = build_given(ctx)
    gravity = build_gravity(ctx)
    body_names = declared_bodies(ctx)  # with the arm's links: springs, loads, ... may refer to them
    bodies = build_bodies(ctx)
    used: dict[str, str] = {}  # coordinate -> the joint it drives (arm rows and joints alike)
    arm_bodies, arm_joints, arm_table = build_arm(ctx, used)
    tree_joints, placed = build_joints(ctx, body_names, arm_joints, used)
    springs, dampers = build_elements(ctx, body_names)
    loads = build_loads(ctx, body_names)
    generalized_forces = build_generalized_forces(ctx)
    kinetic, potential = build_energy(ctx, body_names)
    check_explicit_placement(ctx, placed)
    loop_joints = build_loop_joints(ctx, body_names)
    constraints = build_constraints(ctx)
    independent = build_independent_coordinates(ctx, constraints, len(loop_joints))
    figure = build_figure(ctx)
    simulation = build_simulate(ctx)
    analysis = build_analysis(ctx)
    marking = build_marking(ctx)
    texts = build_texts(ctx)  # last: their maths may use every declared name
    ask = build_ask(ctx, bool(ctx.coords))
    methods = build_methods(ctx, ask)  # after `ask`: Newton-Euler needs equations of motion asked for
    conventions = build_conventions(ctx, ask)  # after `ask`: a convention for symbols not asked for is an error
    check_prescribed(ctx)  # after everything: what a driven coordinate rules out
    if ctx.errors:
        raise SpecErrors(ctx.errors)

    # each coordinate's dimension is known only now (a joint may have given it)
    coordinates = coordinates_with_dimensions(ctx)
    joints = [
        dataclasses.replace(j, coordinate=coordinates[j.coordinate.name]) if j.coordinate is not None else j
        for j in arm_joints + tree_joints
    ]
    system = System(
        title=title,
        statement=statement,
        source=smap.path,
        parameters=tuple(parameters),
        coordinates=tuple(coordinates.values()),
        arm=arm_table,
        bodies=tuple(arm_bodies + bodies),  # the arm first: bodies in `bodies` may hang from its links
        joints=tuple(joints),
        gravity=gravity,
        springs=tuple(springs),
        dampers=tuple(dampers),
        loads=tuple(loads),
        generalized_forces=tuple(generalized_forces),
        kinetic_energy=kinetic,
        potential_energy=potential,
        ask=ask,
        methods=methods,
        origin=smap.location(()),
        significant_figures=ctx.doc.significant_figures,
        figure=figure,
        simulation=simulation,
        marking=marking,
        question_title=question_title,
        given=given,
        conventions=conventions,
        analysis=analysis,
        constraints=tuple(constraints),
        independent_coordinates=independent,
        loop_joints=tuple(loop_joints),
    )
    return with_texts(system, texts)
