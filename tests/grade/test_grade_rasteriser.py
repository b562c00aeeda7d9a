"""Grading workers and Mesa's software rasteriser: workers that fill the machine's cores draw
in their own thread instead of each starting a rasteriser thread per core (LP_NUM_THREADS)."""

from __future__ import annotations

import os

from bras_kit.grade.runner import executor, rasteriser_threads


def test_workers_filling_the_cores_rasterise_in_their_own_thread_and_fewer_share_the_rest(monkeypatch):
    monkeypatch.setattr(os, "cpu_count", lambda: 8)
    assert [rasteriser_threads(n) for n in (1, 2, 3, 4, 8, 16)] == ["8", "4", "2", "2", "0", "0"]
    monkeypatch.setattr(os, "cpu_count", lambda: 2)
    assert [rasteriser_threads(n) for n in (1, 2, 3)] == ["2", "0", "0"]


def test_a_pool_worker_gets_its_share_unless_the_user_chose(monkeypatch):
    monkeypatch.delenv("LP_NUM_THREADS", raising=False)
    cores = os.cpu_count() or 1
    with executor(jobs=cores) as pool:
        assert pool.submit(os.getenv, "LP_NUM_THREADS").result(timeout=60) == "0"
    monkeypatch.setenv("LP_NUM_THREADS", "3")
    with executor(jobs=cores) as pool:
        assert pool.submit(os.getenv, "LP_NUM_THREADS").result(timeout=60) == "3"
