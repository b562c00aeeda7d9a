"""The last cell of a lesson: the exercises of ``bras-kit exercises`` that practise it, read from
the track's own manifests (each names its lesson), so the two never disagree."""

from __future__ import annotations

from ._cells import Lesson, md


def track_cell(lesson: Lesson):  # type: ignore[no-untyped-def]
    from bras_kit.exercises import load_track

    fr_name, en_name = lesson.filename("fr"), lesson.filename("en")
    exercises = [e for e in load_track().exercises
                 if e.lesson_in("fr").endswith("/" + fr_name) or e.lesson_in("en").endswith("/" + en_name)]
    if not exercises or lesson.folder:
        return None
    fr = "\n".join(f"- {e.number}. {e.title_in('fr')}" for e in exercises)
    en = "\n".join(f"- {e.number}. {e.title_in('en')}" for e in exercises)
    return md(
        f"""
        ## À vous : le parcours d'exercices

        Cette leçon se pratique sur vos propres fichiers dans le parcours `bras-kit exercises`
        (sa page : `docs/cli/exercises.md`) :

{_indent(fr)}

        Dans un terminal, à côté de votre éditeur : chaque enregistrement est revérifié, la touche `h`
        donne l'indice suivant.

        ```bash
        bras-kit exercises init exos --lang fr
        cd exos && bras-kit exercises --lang fr
        ```
        """,
        f"""
        ## Your turn: the exercise track

        This lesson is practised on your own files in the `bras-kit exercises` track
        (its page: `docs/cli/exercises.md`):

{_indent(en)}

        In a terminal beside your editor: every save is checked again, the key `h` gives the next
        hint.

        ```bash
        bras-kit exercises init exos --lang en
        cd exos && bras-kit exercises --lang en
        ```
        """,
    )


def _indent(text: str) -> str:
    return "\n".join("        " + line for line in text.splitlines())
