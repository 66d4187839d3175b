"""One problem of one variant as an :class:`~tutgen.lms.questions.LmsQuestion`: run in the sheet's workers.

It reuses what the worker has already made for the sheets: the problem's view (statement, data, the
worked solution's sections), the answer key's results and the marking key's text.
"""

from __future__ import annotations

from typing import Any

import yaml

from tutgen.lms.html import FIGURE_MARK
from tutgen.lms.questions import LmsQuestion, parts_of

_ENV: list[Any] = []


def _render(template: str, problem: dict[str, Any]) -> str:
    if not _ENV:
        from tutgen.render.env import markdown_env

        _ENV.append(markdown_env())
    return str(_ENV[0].get_template(template).render(problem=problem))


def lms_question(
    *,
    key: str,
    view: dict[str, Any],
    results_yaml: str,
    marking_yaml: str,
    system: Any,
    variant: str,
    label: str,
) -> LmsQuestion:
    """The LMS question of problem ``key`` (its sheet view ``view``) in one variant; ``results_yaml`` and
    ``marking_yaml`` are the variant's answer-key results and marking key as the sheet writes them."""
    from tutgen.figure.view import svg_file
    from tutgen.sheet.render import as_set

    figure = None
    generated = system.figure is None or system.figure.generated  # as the sheets decide (sheet/build.py)
    made = svg_file(as_set(system)) if generated else None
    if made is not None:
        figure = (f"{key}.svg", made[1])
    shown = {**view["figure"], "generated": figure is not None, "file_md": False}
    shown["svg"] = f"{FIGURE_MARK}{figure[0]}" if figure else ""
    # the Newton–Euler free-body diagrams are TikZ pictures of the LaTeX sheets: left out, as in Markdown
    solution = view["solution"]
    # (a sheet may set one beside its list of forces: the list is kept, tutgen/sheet/compact.py)
    sections = [
        {
            **sec,
            "blocks": [b["right"] if b["kind"] == "beside" else b for b in sec["blocks"] if b["kind"] != "freebody"],
        }
        for sec in solution["sections"]
    ]
    problem = {**view, "figure": shown, "solution": {**solution, "sections": sections}}
    results = yaml.safe_load(results_yaml)  # tutgen's own output, read back safely
    marking = yaml.safe_load(marking_yaml)
    parts = parts_of(results, marking or {})
    return LmsQuestion(
        problem=key,
        number=int(view["number"]),
        variant=variant,
        label=label,
        title=str(view["question_title"]),
        question_md=_render("lms-question.md.j2", problem),
        feedback_md=_render("lms-feedback.md.j2", problem),
        figure=figure,
        parts=parts,
    )
