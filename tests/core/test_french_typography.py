"""French typography in every catalog: a space before ``:`` ``;`` ``?`` ``!``.

The oracle is the rule of French typography (Imprimerie nationale, *Lexique des règles
typographiques*): the high punctuation marks take a space before them. The test reads every
``.po`` with Babel's ``read_po`` and looks at each translation, leaving alone what is not prose:
Python lines of the package's templates, code spans in backquotes, URLs, xacro's ``:=``,
placeholders such as ``{value:.3g}``, entity references such as ``&nom;`` and dictionary keys
such as ``"time":``.
"""

from __future__ import annotations

import re
from pathlib import Path

import pytest
from babel.messages.pofile import read_po
from paths import REPO, TESTS

CATALOGS = sorted((REPO / "bras_kit" / "locale" / "fr" / "LC_MESSAGES").glob("*.po"))

_CODE_LINE = re.compile(r"^\s*(def|class|if|elif|else|for|while|with|try|except|return|import|from)\b"
                        r"|^\s*[A-Za-z_][\w.\[\]']*\s*=\s")
_NOT_PROSE = re.compile(
    r"`[^`\n]*`"  # a code span
    r"|«[^»\n]*»"  # quoted matter: what the learner wrote or types, as written
    r"|\{[^{}\n]*\}"  # a placeholder, or a dictionary literal on one line
    r"|[a-z]+://\S*"  # a URL
    r"|:=|::|:all:"  # xacro's arguments, C++ scopes, pip's --only-binary=:all:
    r"|&#?\w*(\.\.\.)?;"  # an entity reference
    r"|[\"'][\w-]+[\"']:"  # a key in a dictionary or JSON object
)
_SLIP = re.compile(r"(?<=[^\s\u00a0\u202f])[:;?!](?=\s|$)")


def slips(text: str) -> list[str]:
    """Each place in ``text`` where a high punctuation mark is glued to the word before it."""
    found = []
    for line in text.splitlines():
        if _CODE_LINE.match(line):
            continue
        prose = _NOT_PROSE.sub(lambda m: "x" * len(m.group()), line)  # "{folder}:" is glued too
        for slip in _SLIP.finditer(prose):
            found.append(line[max(0, slip.start() - 25):slip.end() + 10])
    return found


def _translations(path: Path) -> list[tuple[str, str]]:
    with path.open("rb") as handle:
        catalog = read_po(handle, locale="fr")
    out = []
    for message in catalog:
        if not message.id:
            continue
        msgid = message.id[0] if isinstance(message.id, (tuple, list)) else message.id
        strings = message.string if isinstance(message.string, (tuple, list)) else (message.string,)
        out.extend((str(msgid), str(s)) for s in strings if s)
    return out


def test_the_checker_sees_a_glued_colon_and_leaves_code_alone() -> None:
    assert slips("valeur par défaut: 0") == ["valeur par défaut: 0"]
    assert slips("Pourquoi?") and slips("attention!") and slips("a; b")
    assert slips("valeur par défaut : 0") == []
    assert slips("xacro bras.urdf.xacro longueur:=0.8") == []
    assert slips("voir https://docs.ros.org/en/jazzy/ ; ou `needs_package: true`") == []
    assert slips("    if vitesse is not None:") == []
    assert slips("{value:.3g} m") == []
    assert slips("créé dans {folder}:") == ["créé dans {folder}:"]
    assert slips("une référence &nom; ou &#...; ici") == []


@pytest.mark.parametrize("path", CATALOGS, ids=lambda p: p.name)
def test_high_punctuation_takes_a_space_before_it(path: Path) -> None:
    wrong = [f"{msgid[:50]!r}: ...{slip}..." for msgid, text in _translations(path) for slip in slips(text)]
    assert not wrong, f"{path.name}: {len(wrong)} glued punctuation marks:\n" + "\n".join(wrong)


# ------------------------------------------------------------ what commands print, in French

_LOCATION = re.compile(r"^\s*\S+\.(urdf|xacro|py|xml|sdf|yaml):\d+(:\d+)?:")  # a compiler-style place
_DATA = TESTS / "data"


@pytest.mark.parametrize("argv", [
    ("reach", "{arm}", "-0.5", "0", "0.5"),  # the other elbow's solution past the limits
    ("reach", "{arm}", "0.6", "0", "0.9", "--duration", "0.2"),  # an error: "bras-kit reach : erreur : ..."
    ("gazebo", str(_DATA / "gazebo" / "forearm_without_inertial.urdf")),
    ("mjcf", str(_DATA / "gazebo" / "no_inertial_anywhere.urdf"), "-o", "{tmp}/arm.xml"),
    ("doctor",),
], ids=lambda argv: argv[0])
def test_what_commands_print_in_french_has_spaced_colons(argv, run_cli, tmp_path) -> None:
    """Labels composed in code (``warning: ...``, ``tip: ...``) follow the catalog's typography too."""
    arm = _DATA / "launch" / "tutorial" / "bras_description" / "urdf" / "bras.urdf"
    code, out, err = run_cli("--lang", "fr", *(a.format(arm=arm, tmp=tmp_path) for a in argv))
    assert "Traceback" not in err
    lines = [line for line in (out + err).splitlines() if line.strip() and not _LOCATION.match(line)]
    assert lines, (code, out, err)
    wrong = [slip for line in lines for slip in slips(line)]
    assert not wrong, "\n".join(wrong) + "\n---\n" + out + err
