"""The reports of a graded class: grades.csv for the course platform, results.json (or
Gradescope's shape), and static HTML pages, openable from disk."""

from __future__ import annotations

import html
import json
import os
from collections import Counter
from collections.abc import Callable, Sequence
from typing import Any

from ..core.message import M, Message, Mn
from ..trust.inert import Cell, csv_text
from .rubric import SEVERITIES, Item, Rubric, rubric_words

REPORT_MARK = ".bras-kit-grade"  # a folder holding this file is a report bras-kit may refresh


def grades_csv(results: Sequence[dict[str, Any]], rubric: Rubric) -> str:
    """identifier, score, max, one column per rubric item, the first error message; and the
    exercises passed when a learner handed in a ``bras-kit exercises`` track.

    The folder's name, the error and the rubric's ids are strangers' text: bras_kit.trust.inert.csv_text
    makes every text cell inert for a spreadsheet, whatever it splits on, and keeps the numbers."""
    track = any(result.get("exercises") for result in results)
    rows: list[list[Cell]] = [["identifier", "score", "max", *[item.id for item in rubric.items], "first_error",
                               *(["exercises"] if track else [])]]
    for result in results:
        rows.append([str(result["learner"]), float(result["score"]), float(result["max"]),
                     *[float(result["items"].get(item.id, 0.0)) for item in rubric.items],
                     str(result.get("first_error", "")),
                     *([str(result.get("exercises", ""))] if track else [])])
    return csv_text(rows, number_format="g")


def results_json(results: Sequence[dict[str, Any]], rubric: Rubric) -> str:
    return json.dumps({"rubric": {"name": rubric.name, "digest": rubric.digest, "max": rubric.total,
                                  "items": [{"id": i.id, "title": i.title, "points": i.points} for i in rubric.items]},
                       "learners": list(results)}, indent=1, ensure_ascii=False) + "\n"


def gradescope_json(result: dict[str, Any], rubric: Rubric, lang: str | None = None) -> str:
    """One learner's results.json in the shape Gradescope's autograder reads."""
    from ..core.i18n import say

    tests = [{"name": say(rubric_words(item.title), lang), "score": result["items"].get(item.id, 0.0),
              "max_score": item.points, "output": _item_output(item, result, lang)} for item in rubric.items]
    return json.dumps({"score": result["score"], "tests": tests,
                       "output": result.get("first_error") or ""}, indent=1, ensure_ascii=False) + "\n"


def _item_output(item: Item, result: dict[str, Any], lang: str | None) -> str:
    """What the learner reads under one Gradescope test: why it was not earned."""
    if result["status"] != "graded":
        return str(result.get("first_error", ""))
    if item.check == "no_findings":
        floor = SEVERITIES[item.severity]
        hits = [f for f in result["findings"] if SEVERITIES.get(f["severity"], 0) >= floor
                and (not item.codes or f["code"].startswith(item.codes))]
        return "\n".join(f"{f['code']} {f['file']}{':' + str(f['line']) if f.get('line') else ''}: {f['message']}"
                         + (f" ({f['hint']})" if f.get("hint") else "") for f in hits)
    if result["items"].get(item.id, 0.0) < item.points:
        from ..core.i18n import say

        return say(M("not met: {title}", title=rubric_words(item.title)), lang)
    return ""


def _number(value: float) -> str:
    return f"{value:g}"


def _page(title: str, body: str, lang: str) -> str:
    return (f"<!doctype html>\n<html lang='{lang}'><head><meta charset='utf-8'><title>{html.escape(title)}</title>"
            "<style>body{font-family:sans-serif;max-width:60em;margin:2em auto;padding:0 1em;color:#222}"
            "table{border-collapse:collapse}td,th{border:1px solid #ccc;padding:.3em .6em;text-align:left}"
            ".error{color:#c62828}.warning{color:#e65100}.info{color:#455a64}img{max-width:100%;border:1px solid #ddd}"
            "</style></head><body>\n" + body + "\n</body></html>\n")


_NO_PICTURE = {False: M("no picture: the robot could not be read"),
               True: M("no picture (--no-pictures, or the arm could not be drawn)")}


def learner_page(result: dict[str, Any], rubric: Rubric, t: Callable[[Message | str], str], lang: str) -> str:
    rows = "".join(f"<tr><td>{html.escape(t(rubric_words(item.title)))}</td><td>{_number(result['items'].get(item.id, 0.0))}"
                   f" / {_number(item.points)}</td></tr>" for item in rubric.items)
    picture = (f"<p><img src='../{html.escape(result['picture'])}' alt='{html.escape(result['learner'])}'></p>"
               + (f"<p><img src='../{html.escape(result['animation'])}' alt='{html.escape(t(M('the arm moving')))}'></p>"
                  if result.get("animation") else "")
               if result.get("picture") else f"<p><i>{html.escape(t(_NO_PICTURE[result['status'] == 'graded']))}</i></p>")
    findings = "".join(
        f"<li><b class='{html.escape(f['severity'])}'>{html.escape(f['code'])}</b> "
        f"{html.escape(f['file'] or '')}{':' + str(f['line']) if f.get('line') else ''} — {html.escape(f['message'])}"
        + (f"<br><small>{html.escape(t(M('fix')))}: {html.escape(f['hint'])}</small>" if f.get("hint") else "")
        + "</li>" for f in result["findings"])
    body = (f"<p><a href='../index.html'>← {html.escape(t(M('class summary')))}</a></p>"
            f"<h1>{html.escape(result['learner'])}: {_number(result['score'])} / {_number(result['max'])}</h1>"
            + picture + f"<h2>{html.escape(t(M('Score')))}</h2><table>{rows}</table>"
            + f"<h2>{html.escape(t(M('Findings')))}</h2>"
            + (f"<ul>{findings}</ul>" if findings else f"<p>{html.escape(t(M('No finding')))}</p>"))
    return _page(result["learner"], body, lang)


def histogram_svg(scores: Sequence[float], total: float, width: int = 480, height: int = 160) -> str:
    """Learners per score bin, as an inline SVG bar chart (no script, no external file)."""
    bins = max(1, min(10, int(total) or 1))
    counts = [0] * bins
    for score in scores:
        k = min(int(bins * score / total), bins - 1) if total > 0 else 0
        counts[k] += 1
    top = max(counts) or 1
    bar = width / bins
    parts = [f"<svg xmlns='http://www.w3.org/2000/svg' width='{width}' height='{height + 20}' role='img'>"]
    for k, count in enumerate(counts):
        h = (height - 10) * count / top
        parts.append(f"<rect x='{k * bar + 2:.1f}' y='{height - h:.1f}' width='{bar - 4:.1f}' height='{h:.1f}' "
                     f"fill='#1f77b4'><title>{count}</title></rect>")
        parts.append(f"<text x='{k * bar + bar / 2:.1f}' y='{height + 14}' font-size='11' text-anchor='middle'>"
                     f"{total * k / bins:g}–{total * (k + 1) / bins:g}</text>")
    parts.append("</svg>")
    return "".join(parts)


def first_problem(result: dict[str, Any]) -> str:
    """The first error of a learner's findings, else the first warning (a learner who lost points
    on warnings alone must see why in the class table); else what stopped the grading, if anything."""
    for severity in ("error", "warning"):
        for found in result.get("findings", []):
            if found.get("severity") == severity:
                return f"{found['code']} {found['message']}"
    return str(result.get("first_error", ""))


def index_page(results: Sequence[dict[str, Any]], rubric: Rubric, t: Callable[[Message | str], str], lang: str,
               finished: bool) -> str:
    rows = "".join(
        f"<tr><td><a href='learners/{html.escape(_file_name(r['learner']))}'>{html.escape(r['learner'])}</a></td>"
        f"<td>{_number(r['score'])} / {_number(r['max'])}</td><td>{html.escape(first_problem(r))}</td></tr>"
        for r in results)
    hits = Counter(f["code"] for r in results for f in {(x["code"]): x for x in r["findings"]}.values())
    rules = "".join(f"<tr><td>{html.escape(code)}</td><td>{count}</td></tr>" for code, count in sorted(hits.items()))
    note = "" if finished else f"<p class='warning'>{html.escape(t(M('interrupted: only the learners below were graded')))}</p>"
    body = (f"<h1>{html.escape(t(rubric_words(rubric.name)))}</h1>" + note
            + f"<p>{html.escape(t(Mn('{n} learner', '{n} learners', len(results))))}</p>"
            + f"<h2>{html.escape(t(M('Scores')))}</h2>" + histogram_svg([r["score"] for r in results], rubric.total)
            + f"<table><tr><th>{html.escape(t(M('learner')))}</th><th>{html.escape(t(M('score')))}</th>"
              f"<th>{html.escape(t(M('first problem')))}</th></tr>{rows}</table>"
            + f"<h2>{html.escape(t(M('Learners hitting each rule')))}</h2>"
            + (f"<table><tr><th>{html.escape(t(M('rule')))}</th><th>{html.escape(t(M('learners')))}</th></tr>{rules}</table>"
               if rules else f"<p>{html.escape(t(M('No finding')))}</p>"))
    return _page(t(rubric_words(rubric.name)), body, lang)


def _file_name(learner: str) -> str:
    from .worker import _safe_name

    return _safe_name(learner) + ".html"


def _check_own_files(results: Sequence[dict[str, Any]]) -> None:
    """Refuse a class where two learners would share a page or a results file, even on a file
    system that ignores case (file_stem makes that a SHA-256 collision: this is the net under it)."""
    from ..core.errors import BrasKitError

    owners: dict[str, str] = {}
    for result in results:
        learner = str(result["learner"])
        page = _file_name(learner)
        other = owners.setdefault(page.casefold(), learner)
        if other != learner:
            raise BrasKitError(M("learners '{first}' and '{second}' would share the report page {page}",
                                 first=other, second=learner, page=page),
                               hint=M("rename one of their submissions and grade again"))


def write_reports(folder: str, results: Sequence[dict[str, Any]], rubric: Rubric, lang: str, *,
                  gradescope: bool = False, finished: bool = True) -> None:
    from ..core.i18n import say
    from ..trust.outputs import write_text

    def t(words: Message | str) -> str:
        return say(words, lang)

    _check_own_files(results)
    os.makedirs(os.path.join(folder, "learners"), exist_ok=True)
    write_text(os.path.join(folder, "grades.csv"), grades_csv(results, rubric), True, announce=False)
    write_text(os.path.join(folder, "results.json"), results_json(results, rubric), True, announce=False)
    if gradescope:
        os.makedirs(os.path.join(folder, "gradescope"), exist_ok=True)
        for result in results:
            write_text(os.path.join(folder, "gradescope", _file_name(result["learner"])[:-5] + ".json"),
                       gradescope_json(result, rubric, lang), True, announce=False)
    for result in results:
        write_text(os.path.join(folder, "learners", _file_name(result["learner"])),
                   learner_page(result, rubric, t, lang), True, announce=False)
    write_text(os.path.join(folder, "index.html"), index_page(results, rubric, t, lang, finished), True, announce=False)
    write_text(os.path.join(folder, REPORT_MARK), "bras-kit grade report\n", True, announce=False)


def previous_results(folder: str) -> dict[str, dict[str, Any]]:
    """learner -> result of the report already in ``folder`` (for --resume)."""
    try:
        with open(os.path.join(folder, "results.json"), encoding="utf-8") as handle:
            data = json.load(handle)
        return {r["learner"]: r for r in data.get("learners", []) if isinstance(r, dict) and "learner" in r}
    except (OSError, ValueError, AttributeError):
        return {}
