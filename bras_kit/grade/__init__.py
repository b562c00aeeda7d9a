"""Grading a class: submissions checked, drawn and scored by a rubric, on a local process
pool or a Dask cluster, with reports for the course platform and for people."""

from __future__ import annotations

from .report import write_reports
from .rubric import DEFAULT_RUBRIC, Item, Rubric, load_rubric
from .runner import executor, grade_all
from .submissions import Submission, find_submissions, unpack
from .worker import Options, grade, node_containment, passes

__all__ = ["DEFAULT_RUBRIC", "Item", "Options", "Rubric", "Submission", "executor", "find_submissions", "grade",
           "grade_all", "load_rubric", "node_containment", "passes", "unpack", "write_reports"]
