"""Help that reads as a user would: metavars (``SPEC...``, ``FILE``, ``SECONDS``), never Python types.

Typer prints an argument with its annotation (``specs... <list[Path]>``) and its usage as ``{specs}...``,
and a bounded number as ``x>=0``. :class:`Command` prints the argument's metavar (or its name in
capitals) instead, in the usage line and the list alike, and a bound in words ("at least 0",
"1 to 10000"). Options state their own ``metavar``; tests/cli/test_help.py reads every command's
``--help`` for leaks.
"""

from __future__ import annotations

import re
from typing import TYPE_CHECKING

import typer.core

if TYPE_CHECKING:  # annotations only: typer >= 0.16 carries its own click, and click is not a dependency
    import click

#: Click's and Typer's texts of a bound (``x>=0``, ``1<=x<=10000``) inside a help's ``[...]``
_RANGE = re.compile(
    r"(?:(?P<lo>-?[0-9.e+-]+)<=x<=(?P<hi>-?[0-9.e+-]+)|x>=(?P<min>-?[0-9.e+-]+)|x<=(?P<max>-?[0-9.e+-]+))"
)


def _bound_in_words(match: re.Match[str]) -> str:
    if match["lo"] is not None:
        return f"{match['lo']} to {match['hi']}"
    if match["min"] is not None:
        return f"at least {match['min']}"
    return f"at most {match['max']}"


def argument_name(param: click.Parameter) -> str:
    """``SPEC...``: the metavar if given, else the name in capitals, with ``...`` for several values."""
    name = param.metavar or (param.name or "").upper()
    if param.nargs != 1 and not name.endswith("..."):
        name += "..."
    return name


class Command(typer.core.TyperCommand):
    """A Typer command whose help names arguments by their metavars and bounds in words."""

    def collect_usage_pieces(self, ctx: click.Context) -> list[str]:
        pieces = [self.options_metavar] if self.options_metavar else []
        for param in self.get_params(ctx):
            if param.param_type_name == "argument":
                name = argument_name(param)
                pieces.append(name if param.required else f"[{name}]")
        return pieces

    def format_options(self, ctx: click.Context, formatter: click.HelpFormatter) -> None:
        args: list[tuple[str, str]] = []
        opts: list[tuple[str, str]] = []
        for param in self.get_params(ctx):
            record = param.get_help_record(ctx)
            if record is None:
                continue
            name, text = record
            text = _RANGE.sub(_bound_in_words, text)
            if param.param_type_name == "argument":
                args.append((argument_name(param), text))
            else:
                opts.append((name, text))
        if args:
            with formatter.section("Arguments"):
                formatter.write_dl(args)
        if opts:
            with formatter.section("Options"):
                formatter.write_dl(opts)
