"""Sheets as text: the question sheet, the solution sheet and the answer keys of one variant.

The template context of a sheet (templates/{markdown,latex}/sheet-*.j2), plain data only:

- ``title``, ``course``, ``date``, ``label`` (the variant's label or the student's name; may be empty),
  ``kind`` (set by the template: "questions" or "worked solutions");
- ``problems``: one mapping per problem, in sheet order, with ``number``, ``title`` (the solution's) and
  ``question_title`` (the question sheet's: the spec's ``question_title``, else its ``title``),
  ``statement``, ``statement_parts`` (its placeholders ``{m}`` filled with this variant's values),
  ``given`` and ``coordinates`` (lists of parts, as in tutgen/render/views.py; the statement's ``$…$``
  maths typeset), ``question_coordinates`` (the coordinates as the question sheet states them: none when
  the spec's ``given: {coordinates: false}`` leaves them to the student), ``asked`` (texts) and
  ``asked_parts`` (the same as lists of
  parts, maths typeset), ``figure`` (the problem's figure, as in tutgen/figure/view.py), and
  ``solution``: the worked solution's context from :func:`tutgen.render.views.solution_view`
  (``sections``, ``remarks``, ``checks``), its blocks set more tersely (tutgen/sheet/compact.py).

Text is raw (the templates escape it); maths is LaTeX.
"""

from __future__ import annotations

from collections.abc import Sequence
from typing import Any

from tutgen.engine.derivation import Derivation
from tutgen.memo import ByIdentity
from tutgen.model.marking import Marking
from tutgen.model.system import Ask
from tutgen.render.blocks import prose, rich
from tutgen.render.printer import TexPrinter
from tutgen.render.views import coordinate_items, given_items
from tutgen.sheet.compact import compact_sections, shared_intros

#: What each item of a spec's ``ask`` asks for, as a question sheet words it (maths between ``$``, LaTeX).
ASKED = {
    Ask.INERTIA: "the mass, centre of mass and inertia tensor of each body",
    Ask.KINETIC_ENERGY: "the kinetic energy",
    Ask.POTENTIAL_ENERGY: "the potential energy",
    Ask.LAGRANGIAN: "the Lagrangian",
    Ask.LAGRANGE_EQUATIONS: "Lagrange's equations, term by term",
    Ask.EQUATIONS_OF_MOTION: "the equations of motion",
    Ask.MATRIX_FORM: "the matrix form $H(q)\\ddot q + C(q,\\dot q) + G(q) = Q$",
    Ask.CHRISTOFFEL: "the Christoffel symbols",
    Ask.SIMULATION: "a numerical simulation of the motion: $q(t)$, $\\dot q(t)$ and the energy",
    Ask.EQUILIBRIA: "the equilibria and their stability",
    Ask.LINEARIZATION: "the linear model about the equilibrium, its eigenvalues and stability",
    Ask.MOMENTUM: "the linear and angular momentum of each body and in total",
    Ask.STEADY_MOTION: "the steady motions at constant rates of the cyclic coordinates and their stability",
}


#: what a question asks first when it leaves the coordinates to the student (``given: {coordinates: false}``)
ASKED_COORDINATES = "a choice of generalized coordinates (propose them)"


def problem_view(number: int, derivation: Derivation, solution: bool) -> dict[str, Any]:
    """One problem of a sheet: as set and, for the solution sheet, its worked solution."""
    from tutgen.render.views import solution_view

    s = derivation.system
    view = solution_view(derivation, decimals=True) if solution else None
    coords = coordinate_items(s)
    asked_text = [ASKED[a] for a in Ask if a in s.ask]
    proposed = not s.given.coordinates and bool(s.coordinates)  # the student is to propose them
    if proposed:
        asked_text.insert(0, ASKED_COORDINATES)
    if asked_text:  # a sentence: "Asked. The kinetic energy; the potential energy."
        asked_text[0] = asked_text[0][:1].upper() + asked_text[0][1:]
    asked = [a.replace("$", "") for a in asked_text]  # the plain wording (maths as LaTeX source)
    return {
        "number": number,
        "title": s.title,
        "question_title": s.question_title or s.title,
        "statement": s.statement or "",
        "statement_parts": rich(s.statement or "", TexPrinter(s)),
        "given": given_items(s),
        "coordinates": coords,
        "question_coordinates": [] if proposed else coords,
        "asked": asked,
        "figure": _figure(as_set(s)),  # tutgen/figure/view.py: the LaTeX sheets set it beside the problem
        "asked_parts": [prose(a) for a in asked_text],
        "solution": {
            # a sheet sets the same steps more tersely than a single solution (tutgen/sheet/compact.py)
            "sections": compact_sections(view["sections"]) if view else [],
            "remarks": view["remarks"] if view else [],
            "checks": view["checks"] if view else [],
        },
    }


def as_set(system: Any) -> Any:
    """The system as the question sheet names it: its ``question_title`` as its title, for what both sheets
    share (the figure's caption and its SVG's title), so that neither gives the answer away. The same
    object for the same system (the last few remembered), so that its figure is drawn once
    (tutgen.figure.build.draw_system remembers a drawing per system object)."""
    import dataclasses

    if not system.question_title:
        return system
    shown = _AS_SET.get(system)
    return shown if shown is not None else _AS_SET.put(system, dataclasses.replace(system, title=system.question_title))


_AS_SET: ByIdentity[Any, Any] = ByIdentity(64)


def _figure(system: Any) -> dict[str, Any]:
    from tutgen.figure.view import figure_view

    return figure_view(system)


def sheet_context(
    header: dict[str, str], derivations: Sequence[Derivation], solution: bool, views: list[dict[str, Any]] | None = None
) -> dict[str, Any]:
    problems = views if views is not None else [problem_view(i + 1, d, solution) for i, d in enumerate(derivations)]
    return {**header, "problems": shared_intros(problems)}


_ENVS: dict[str, Any] = {}


def _sheet_env(fmt: str) -> Any:
    """The environment of the shipped templates of ``fmt`` ("md" or "tex"), one per process: each template
    is compiled once, and never looked at again on disk (a sheet includes a block's template 18 000 times
    for 100 variants, and Jinja's default ``auto_reload`` stats the file each time)."""
    from tutgen.render.env import latex_env, markdown_env

    if fmt not in _ENVS:
        env = markdown_env() if fmt == "md" else latex_env()
        env.auto_reload = False
        _ENVS[fmt] = env
    return _ENVS[fmt]


def render_sheet(context: dict[str, Any], kind: str, fmt: str) -> str:
    """``kind`` "questions" or "solutions", ``fmt`` "md" or "tex" (a PDF compiles the "tex")."""
    ext = "md" if fmt == "md" else "tex"
    return str(_sheet_env(ext).get_template(f"sheet-{kind}.{ext}.j2").render(**context))


def warm_templates(formats: Sequence[str]) -> None:
    """Compile the sheet templates of ``formats`` ("md", "tex", "pdf") in this process, before it forks
    its workers, so that each worker does not compile them again."""
    for fmt in {"md" if f == "md" else "tex" for f in formats}:
        for kind in ("questions", "solutions"):
            _sheet_env(fmt).get_template(f"sheet-{kind}.{fmt}.j2")


def answer_key(results: str | Derivation, spec_name: str, student: str) -> str:
    """The answer key of one problem of one variant, in the answers format of ``tutgen check``
    (docs/check.md): every result of ``tutgen solve --format json``, with this variant's numbers.
    ``results``: the variant's derivation, or the text :func:`key_results` made of it."""
    head = {"spec": spec_name, "student": student}
    text = dump_yaml(head, flow=False)
    text += results if isinstance(results, str) else key_results(results)
    return f"# The answer key of {spec_name}: check it with `tutgen check {spec_name} THIS_FILE`.\n" + text


def key_results(derivation: Derivation, results: dict[str, Any] | None = None) -> str:
    """The results part of an answer key (YAML); ``results``: :func:`results_json` of the derivation,
    when the caller has it already."""
    results = results if results is not None else results_json(derivation)
    ne = results.get("newton_euler")
    if isinstance(ne, dict) and "planar" in ne:  # the working of the solution (free bodies in words), not an answer
        results = {**results, "newton_euler": {k: v for k, v in ne.items() if k != "planar"}}
    return dump_yaml(results)


def results_json(derivation: Derivation, working: bool = True) -> dict[str, Any]:
    """``results`` of ``tutgen solve --format json`` (tutgen/render/jsonout.py), without building the
    document's ``steps``, figure and free-body diagrams, which no key holds and no result reads: the steps'
    values and LaTeX were about three quarters of the JSON's time on the tutorial, the figure and the
    diagrams most of the rest. ``working=False``: without the planar Newton–Euler working either, which
    :func:`key_results` leaves out."""
    from tutgen.render.jsonout import results_to_json

    return results_to_json(derivation, working=working)


def marking_key(
    derivation: Derivation, stated: Marking | None, spec_name: str, results: dict[str, Any] | None = None
) -> str:
    """The marking key of one problem of one variant (``tutgen check --key``, docs/check.md): the
    sheet's or the problem's ``marking:``, else the spec's; the items asked (when none is stated, those
    derived from the spec's ``ask``, so that the key says what is graded), and the significant figures
    this variant's solution prints decimals with, so that a decimal copied from it is right."""
    from tutgen.check.verdicts import PRINTED_FIGURES, derived_ask
    from tutgen.spec.builders.marking import marking_data

    system = derivation.system
    marking = stated if stated is not None else system.marking
    data = marking_data(marking) if marking is not None else {}
    note = "as the sheet or the spec states it"
    if "ask" not in data:
        results = results if results is not None else results_json(derivation)
        data = {"ask": list(derived_ask(system, results)), **data}
        note = "the items derived from the spec's ask (no marking: states them)"
    data.setdefault("significant_figures", system.significant_figures or PRINTED_FIGURES)
    head = (
        f"# The marking key of {spec_name} ({note}): mark a student's answers with\n"
        f"# `tutgen check {spec_name} ANSWERS --key THIS_FILE`.\n"
    )
    return head + dump_yaml(data)


def dump_yaml(data: Any, flow: bool = True) -> str:
    """``data`` as the keys' YAML: keys in their order, Unicode as it is, lines of at most 100 characters,
    and (``flow``) short lists and mappings in flow style. PyYAML's libyaml emitter writes the same text
    as its Python emitter about eight times faster (tests/sheet/test_keys.py compares the two on every
    key of the tutorial sheet); the Python one is the fallback where PyYAML was built without libyaml."""
    import yaml

    dumper = getattr(yaml, "CSafeDumper", yaml.SafeDumper)
    options: dict[str, Any] = {"sort_keys": False, "allow_unicode": True, "width": 100}
    if flow:
        options["default_flow_style"] = None
    return yaml.dump(data, Dumper=dumper, **options)
