"""Grading a class: the same code path on a local process pool or a Dask cluster (both are
``concurrent.futures`` executors), a progress bar on a terminal, resume by content hash, and
Ctrl-C keeping what was finished."""

from __future__ import annotations

import concurrent.futures as futures
import contextlib
import os
import sys
import time
from collections.abc import Callable, Iterator, Sequence
from typing import IO, Any

from ..errors import BrasKitError, ParameterError
from .rubric import Rubric
from .submissions import Submission, content_hash
from .worker import Options, grade


@contextlib.contextmanager
def executor(jobs: int | None = None, scheduler: str | None = None) -> Iterator[futures.Executor]:
    """A local process pool of ``jobs`` workers, or the Dask cluster at ``scheduler``."""
    if scheduler:
        try:
            from distributed import Client
        except ImportError:
            raise ParameterError("--scheduler needs Dask's distributed package",
                                 hint="pip install 'bras-kit[cluster]'") from None
        try:
            client = Client(scheduler, timeout=10)
        except (OSError, TimeoutError) as exc:
            raise BrasKitError(f"cannot reach the Dask scheduler {scheduler}: {exc}",
                               hint="start it with 'dask scheduler' and its workers with 'dask worker "
                                    f"{scheduler}'") from None
        try:
            yield client.get_executor()
        finally:
            client.close()
        return
    import multiprocessing

    # fork: workers start at once and share what this process already imported
    pool = futures.ProcessPoolExecutor(max_workers=jobs or os.cpu_count() or 1,
                                       mp_context=multiprocessing.get_context("fork"))
    try:
        yield pool
    finally:
        pool.shutdown(wait=False, cancel_futures=True)


class Progress:
    """done / total, failures and rate on one line of a terminal; nothing when piped."""

    def __init__(self, total: int, stream: IO[str] | None = None) -> None:
        self.stream = stream or sys.stderr
        self.enabled = bool(getattr(self.stream, "isatty", lambda: False)())
        self.total, self.done, self.failed = total, 0, 0
        self.start = time.monotonic()

    def update(self, failed: bool) -> None:
        self.done += 1
        self.failed += int(failed)
        if self.enabled:
            from ..i18n import _

            rate = self.done / max(time.monotonic() - self.start, 1e-6)
            filled = int(30 * self.done / max(self.total, 1))
            self.stream.write("\r" + _("grading [{bar}] {done}/{total}, {failed} unreadable, {rate:.1f}/s ").format(
                bar="#" * filled + "." * (30 - filled), done=self.done, total=self.total, failed=self.failed,
                rate=rate))
            self.stream.flush()

    def close(self) -> None:
        if self.enabled:
            self.stream.write("\n")
            self.stream.flush()


def grade_all(submissions: Sequence[Submission], rubric: Rubric, options: Options, *,
              jobs: int | None = None, scheduler: str | None = None,
              previous: dict[str, dict[str, Any]] | None = None,
              on_result: Callable[[dict[str, Any]], None] | None = None) -> tuple[list[dict[str, Any]], bool]:
    """Results in submission order, and whether the batch ran to the end (False after Ctrl-C).

    ``previous`` (learner -> result of an earlier report) is reused when the submission's
    content hash and the rubric are unchanged (``--resume``).
    """
    results: dict[str, dict[str, Any]] = {}
    todo = []
    for submission in submissions:
        old = (previous or {}).get(submission.learner)
        if old and old.get("hash") == content_hash(submission.path) and old.get("rubric") == rubric.digest \
                and old.get("lang") == options.lang:
            results[submission.learner] = old
        else:
            todo.append(submission)
    progress = Progress(len(submissions))
    for _ in results:
        progress.update(False)
    finished = True
    try:
        with executor(jobs, scheduler) as pool:
            pending = {pool.submit(grade, s, rubric, options): s for s in todo}
            for future in futures.as_completed(pending):
                submission = pending[future]
                try:
                    result = future.result()
                except Exception as exc:  # a worker that died: that learner only
                    result = _failed(submission, rubric, exc)
                result.update(rubric=rubric.digest, lang=options.lang)
                results[submission.learner] = result
                progress.update(result["status"] != "graded")
                if on_result is not None:
                    on_result(result)
    except KeyboardInterrupt:
        finished = False
    finally:
        progress.close()
    ordered = [results[s.learner] for s in submissions if s.learner in results]
    return ordered, finished


def _failed(submission: Submission, rubric: Rubric, exc: BaseException) -> dict[str, Any]:
    return {"learner": submission.learner, "path": submission.path, "hash": content_hash(submission.path),
            "status": "unreadable", "picture": None, "animation": None, "main_file": None, "package": False,
            "findings": [{"file": os.path.basename(submission.path), "line": None, "code": "BK103",
                          "severity": "error", "message": f"could not be graded: {type(exc).__name__}: {exc}",
                          "hint": "check the submission by hand with bras-kit validate"}],
            "items": {item.id: 0.0 for item in rubric.items}, "score": 0.0, "max": rubric.total,
            "first_error": f"BK103 could not be graded: {exc}", "seconds": 0.0}
