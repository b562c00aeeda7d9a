"""The workspace, shell and machine checks as `doctor` and `doctor --ros` print them."""

from __future__ import annotations


def print_surroundings(lang: str | None, *, width: int | None = None, graphics: bool = True,
                       shown: tuple[str, ...] = ("ok", "note", "fail")) -> list:
    """The workspace, shell and machine checks, printed under a title per area; the shown ones returned."""
    from ..core.i18n import labelled, say
    from ..core.message import M
    from ..doctor.install import Check
    from ..doctor.surroundings import AREAS, look

    status_words = {"ok": say(M("ok"), lang), "note": say(M("note"), lang), "fail": say(M("fail"), lang)}
    width = width or max(len(word) for word in status_words.values())
    titles = {"workspace": M("the workspace"), "shell": M("this terminal"), "machine": M("this machine")}
    concerns = [c for c in look(".", graphics=graphics) if c.status in shown]
    for area in AREAS:
        mine = [c for c in concerns if c.area == area]
        if mine:
            print(say(titles[area], lang), flush=True)
        for concern in mine:
            print(f"{status_words[concern.status]:<{width}}  " + labelled(concern.name, say(concern.found, lang), lang),
                  flush=True)
            if concern.fix is not None:
                label = M("fix") if concern.status == "fail" else M("hint")
                print(f"{'':<{width}}  " + labelled(label, say(concern.fix, lang), lang), flush=True)
    return [Check(c.name, c.status, c.found, c.fix) for c in concerns]
