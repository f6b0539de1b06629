"""Shared pytest fixtures: run small decks with the built `lmp` (helpers in lmprun.py)."""
import pytest

from lmprun import run_lmp


@pytest.fixture
def lmp(tmp_path):
    """lmp(deck_text, np=1, omp=0, **vars) runs a deck in a temporary directory."""

    def run(deck, np=1, omp=0, timeout=600, args=(), **variables):
        return run_lmp(deck, tmp_path, np=np, omp=omp, timeout=timeout, args=args, **variables)

    return run
