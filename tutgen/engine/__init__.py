"""The derivation engine: spec model in, derivation steps out (see docs/architecture.md)."""

from tutgen.engine.fastkb import install as _install_fast_kb

_install_fast_kb()  # sympy's assumption tables copied without re-deducing them (tutgen/engine/fastkb.py)
