"""bras-kit doctor: what this install can do (OpenGL, MuJoCo, the browser viewer...) and how to fix the rest."""

from __future__ import annotations

import argparse


def configure(parser: argparse.ArgumentParser) -> None:
    parser.add_argument("--clear-cache", action="store_true",
                        help="remove the decoded meshes kept in the cache folder, then run the checks")


def run(args: argparse.Namespace) -> int:
    from ..doctor import CHECKS, healthy, run_checks
    from ..i18n import labelled, say
    from ..message import M, Mn

    lang = args.lang
    if getattr(args, "clear_cache", False):
        from ..meshes import clear_cache

        removed = clear_cache()
        print(say(Mn("removed {n} decoded mesh ({size:.1f} MB) from {path}",
                     "removed {n} decoded meshes ({size:.1f} MB) from {path}", removed.entries,
                     size=removed.bytes / 1e6, path=removed.folder), lang), flush=True)
    status_words = {"ok": say(M("ok"), lang), "note": say(M("note"), lang), "fail": say(M("fail"), lang)}
    width = max(len(word) for word in status_words.values())
    results = []
    for check in CHECKS:  # one at a time: each line shows as soon as its check is done
        (result,) = run_checks([check])
        results.append(result)
        print(f"{status_words[result.status]:<{width}}  " + labelled(result.name, say(result.found, lang), lang),
              flush=True)
        if result.fix is not None:
            label = M("fix") if result.status == "fail" else M("hint")
            print(f"{'':<{width}}  " + labelled(label, say(result.fix, lang), lang), flush=True)
    failed = sum(result.status == "fail" for result in results)
    if healthy(results):
        print(say(M("everything bras-kit needs works here"), lang))
        return 0
    print(say(Mn("{n} problem to fix: see 'fix' above", "{n} problems to fix: see 'fix' above", failed), lang))
    return 1
