"""The derivation time limit: a slow spec stops cleanly, naming the step it had reached."""

from __future__ import annotations

import threading
import time

import pytest

from tutgen.engine.pipeline import derive_with_deadline
from tutgen.errors import EXIT_CANNOT_DERIVE, DerivationError, DerivationTimeout
from tutgen.limits import DEFAULT_TIMEOUT, checkpoint, current_step, deadline
from tutgen.spec.validate import load_system_text


def spatial_chain(links: int) -> str:
    """A chain of ``links`` point masses whose joint axes alternate z, y, x: slow to derive symbolically."""
    axes = ["z", "y", "x"]
    lines = [
        "tutgen: 1",
        f"title: {links}-link spatial chain",
        "parameters: [g, " + ", ".join(f"m{i}, l{i}" for i in range(1, links + 1)) + "]",
        "coordinates: [" + ", ".join(f"q{i}" for i in range(1, links + 1)) + "]",
        "gravity: [0, 0, -g]",
        "bodies:",
    ]
    for i in range(1, links + 1):
        lines.append(f"  link{i}: {{mass: m{i}, com: [l{i}, 0, 0]}}")
    lines.append("joints:")
    for i in range(1, links + 1):
        parent = "ground" if i == 1 else f"link{i - 1}"
        origin = "[0, 0, 0]" if i == 1 else f"[l{i - 1}, 0, 0]"
        lines.append(
            f"  j{i}: {{type: revolute, parent: {parent}, child: link{i}, axis: {axes[i % 3]}, "
            f"origin: {origin}, coordinate: q{i}}}"
        )
    return "\n".join(lines) + "\n"


def test_limits_slow_spec_stops_cleanly_naming_the_step() -> None:
    system = load_system_text(spatial_chain(7), "chain7.yaml")
    start = time.monotonic()
    with pytest.raises(DerivationTimeout) as info:
        derive_with_deadline(system, "both", 1)
    elapsed = time.monotonic() - start
    assert elapsed < 10, f"the 1 s deadline took {elapsed:.1f} s to stop the derivation"
    err = info.value
    assert isinstance(err, DerivationError)
    assert err.exit_code == EXIT_CANNOT_DERIVE
    assert err.step and err.step != "start"
    assert str(err).startswith("chain7.yaml:1:1: error: the derivation did not finish within 1 s (it was at: ")
    assert str(err).endswith("); simplify the spec or raise --timeout")


def test_limits_deadline_is_disarmed_after_the_block() -> None:
    with deadline(0.2):
        checkpoint("quick")
    time.sleep(0.4)  # no stray alarm afterwards
    assert current_step() == "quick"


def test_limits_zero_none_and_other_threads_are_no_ops() -> None:
    for seconds in (0, None):
        with deadline(seconds):
            time.sleep(0.05)
    errors: list[BaseException] = []

    def worker() -> None:
        try:
            with deadline(0.01):
                time.sleep(0.1)
        except BaseException as exc:  # pragma: no cover - would be the failure
            errors.append(exc)

    thread = threading.Thread(target=worker)
    thread.start()
    thread.join()
    assert not errors


def test_limits_expiry_raises_again_at_the_next_checkpoint() -> None:
    """sympy sometimes catches Exception; a swallowed timeout is raised again at the next step."""
    with pytest.raises(DerivationTimeout, match=r"it was at: step one"), deadline(0.05):
        checkpoint("step one")
        try:
            time.sleep(1)
        except Exception:
            pass
        checkpoint("step two")


def test_limits_default_timeout() -> None:
    assert DEFAULT_TIMEOUT == 120


def test_solve_timeout_option_stops_cleanly(tmp_path) -> None:
    """`tutgen solve --timeout`: exit 4, the step it was at, no traceback, nothing written."""
    from typer.testing import CliRunner

    from tutgen.cli.main import app

    spec = tmp_path / "chain7.yaml"
    spec.write_text(spatial_chain(7), encoding="utf-8")
    out = tmp_path / "out.json"
    result = CliRunner().invoke(app, ["solve", str(spec), "--format", "json", "--timeout", "1", "-o", str(out)])
    assert result.exit_code == 4, result.output
    assert "it was at: " in result.stderr and "Traceback" not in result.stderr
    assert not out.exists()


def test_a_timeout_pickles_with_its_place_and_step() -> None:
    """A sheet's worker sends its timeout to the parent pickled (issue 17: the problems are derived in
    the workers); the parent prints the same text, naming the spec and the step."""
    import pickle

    from tutgen.spec.loader import Location

    for stage in ("derivation", "rendering"):
        err = DerivationTimeout(2.5, "mass matrix", stage)
        err.location = Location("specs/p05.yaml", 1, 1)
        back = pickle.loads(pickle.dumps(err))
        assert type(back) is DerivationTimeout
        assert str(back) == str(err) and "specs/p05.yaml:1:1" in str(back)
        assert (back.seconds, back.step, back.stage) == (2.5, "mass matrix", stage)


def test_a_sheets_workers_keep_the_runs_deadline_and_name_the_spec() -> None:
    """A sheet's problems derived in two workers, inside the run's deadline: the timeout is raised in
    the worker, naming the spec and the step reached, with the run's whole budget (as one worker says)."""
    from tests.conftest import SPECS
    from tutgen.limits import stage
    from tutgen.sheet.build import derive_problems
    from tutgen.sheet.executor import ProcessExecutor
    from tutgen.sheet.model import load_sheet

    sheet = load_sheet(SPECS / "tutorial-1" / "sheet.yaml")
    with pytest.raises(DerivationTimeout) as info:
        with deadline(0.3):
            stage("derivation", "the problems")
            derive_problems(sheet, None, 0.3, ProcessExecutor(2))
    text = str(info.value)
    assert text.startswith("specs/tutorial-1/p0") or "/specs/tutorial-1/p0" in text, text
    assert "did not finish within 0.3 s (it was at: " in text and "(it was at: the problems)" not in text


def test_an_inherited_deadline_in_its_own_process_leaves_the_alarm_armed() -> None:
    """``inherited_deadline`` is for a forked worker; where the deadline is the process's own (a pool of
    one job runs it in the parent) it must not disarm the run's alarm (it did: a sheet of one problem ran
    past --timeout)."""
    from tutgen.limits import inherited_deadline

    start = time.monotonic()
    with pytest.raises(DerivationTimeout):
        with deadline(0.3):
            with inherited_deadline():
                pass
            time.sleep(3)
    assert time.monotonic() - start < 2
