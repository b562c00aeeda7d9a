"""The hostile corpus of tests/hostile_corpus.py, category by category, the jobs set aside last
(issue 53, item 4): every job must hold (no raw terminal control, no canary, no formula cell,
one page per learner, no hang, no traceback, bounded memory, a refusal said aloud). The oracles
are the kernel's (peak RSS by GNU time, FIFOs, links), the canary's bytes and the CSV module's
reading of the files, with ``,`` and with ``;``; none comes from the code under test."""

from __future__ import annotations

import pytest
from hostile_corpus import CATEGORIES, Job, aside_jobs, formula_parts, run_job

pytestmark = pytest.mark.slow


def _held(jobs: list[Job]) -> None:
    verdicts = [run_job(job) for job in jobs]
    for verdict in verdicts:
        print(f"{'held' if verdict.held else 'FAILED'} {verdict.seconds:.1f} s {verdict.rss_mb:.0f} MB "
              f"{verdict.job.name} {verdict.failures}")
    failed = [(v.job.name, v.failures) for v in verdicts if not v.held]
    assert jobs and not failed, f"held {len(verdicts) - len(failed)} of {len(verdicts)}: {failed}"


@pytest.mark.parametrize("category", CATEGORIES, ids=lambda make: make.__name__)
def test_the_corpus_holds(category, tmp_path):
    _held(list(category(tmp_path)))


def test_the_jobs_set_aside_hold(tmp_path):  # last in the file: pytest runs it after the categories
    _held(list(aside_jobs(tmp_path)))


def test_the_formula_oracle_finds_each_start_after_each_separator():
    for separator in ",; \t|:\n\r\"":
        for start in "=+-@\uff1d":
            assert formula_parts(f"ok{separator}{start}1") != [], (separator, start)
            assert formula_parts(f"ok{separator}'{start}1") == [], (separator, start)
    assert formula_parts("-0.5") == [] and formula_parts("plain") == []
