"""bras-kit doctor: what this install can do (OpenGL, MuJoCo, the browser viewer...) and how to fix the rest."""

from __future__ import annotations

import argparse


def configure(parser: argparse.ArgumentParser) -> None:
    del parser  # no options yet: every check runs


def run(args: argparse.Namespace) -> int:
    from ..doctor import CHECKS, healthy, run_checks
    from ..i18n import say
    from ..message import M, Mn

    lang = args.lang
    status_words = {"ok": say(M("ok"), lang), "note": say(M("note"), lang), "fail": say(M("fail"), lang)}
    width = max(len(word) for word in status_words.values())
    results = []
    for check in CHECKS:  # one at a time: each line shows as soon as its check is done
        (result,) = run_checks([check])
        results.append(result)
        print(f"{status_words[result.status]:<{width}}  {say(result.name, lang)}: {say(result.found, lang)}",
              flush=True)
        if result.fix is not None:
            label = say(M("fix") if result.status == "fail" else M("hint"), lang)
            print(f"{'':<{width}}  {label}: {say(result.fix, lang)}", flush=True)
    failed = sum(result.status == "fail" for result in results)
    if healthy(results):
        print(say(M("everything bras-kit needs works here"), lang))
        return 0
    print(say(Mn("{n} problem to fix: see 'fix' above", "{n} problems to fix: see 'fix' above", failed), lang))
    return 1
