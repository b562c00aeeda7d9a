"""Rule texts with a count in them follow it, in English and in French (issue 52).

The oracle is Python's own :mod:`gettext` reading the compiled ``validate.mo`` (so the plural
rule is the one the catalog's ``Plural-Forms`` header gives, not bras-kit's), and English's rule
as :class:`gettext.NullTranslations` applies it; a few sentences are written out by hand. A scan
of every registered text keeps a count from coming back beside a fixed plural noun.
"""

from __future__ import annotations

import gettext
import re
from collections.abc import Iterator, Mapping

import pytest

import bras_kit.validate  # noqa: F401  (registers every family's texts)
from bras_kit.core.i18n import LOCALE_DIR, say
from bras_kit.findings.registry import TEXTS, Plural, Text, count_of, pick, text_message
from bras_kit.validate.catalogue import raw_text

MO = LOCALE_DIR / "fr" / "LC_MESSAGES" / "validate.mo"
COUNTS = (0, 1, 2, 5)
FIELD = re.compile(r"\{([A-Za-z_]\w*)(?:[!:][^{}]*)?\}")
OTHER = 3  # the count given to the counts a case does not vary


@pytest.fixture(scope="module")
def french() -> gettext.GNUTranslations:
    with MO.open("rb") as handle:
        return gettext.GNUTranslations(handle)


ENGLISH = gettext.NullTranslations()


def _texts(code: str) -> Iterator[tuple[str, str, Text]]:
    """``(kind, variant, text)`` for every message and hint of rule ``code``."""
    for kind in ("message", "hint"):
        template = getattr(TEXTS[code], kind)
        variants = template.items() if isinstance(template, Mapping) else [("", template)]
        for variant, text in variants:
            if text:
                yield kind, variant, text


def _forms(text: Text) -> tuple[str, ...]:
    return (text.singular, text.plural) if isinstance(text, Plural) else (text,)


def _fields(text: Text) -> set[str]:
    return {name for form in _forms(text) for name in FIELD.findall(form)}


def _plural_cases() -> list[tuple[str, str, str, Text, str | None]]:
    """Every counted text: ``(code, kind, variant, text, part)``; ``part`` names the counted
    phrase being varied (None: the text's own count)."""
    cases = []
    for code in sorted(TEXTS):
        parts = TEXTS[code].parts
        for kind, variant, text in _texts(code):
            if isinstance(text, Plural):
                cases.append((code, kind, variant, text, None))
            for name in sorted(_fields(text) & set(parts)):
                cases.append((code, kind, variant, text, name))
    return cases


CASES = _plural_cases()


def _oracle(code: str, text: Text, params: Mapping[str, object], lang: str, french: gettext.GNUTranslations) -> str:
    """``text`` worded by the standard library's gettext and ``str.format``, never by bras-kit."""
    table = ENGLISH if lang == "en" else french
    if isinstance(text, Plural):
        n = params[text.n]
        template = table.npgettext(code, text.singular, text.plural, len(n) if isinstance(n, list) else n)
    else:
        template = table.pgettext(code, text)
    return template.format(**params)


def _params(code: str, text: Text, counted: str, n: int) -> dict[str, object]:
    """A value for every field: ``counted`` = ``n``, the other counts 3, the rest a marker."""
    parts = TEXTS[code].parts
    names = _fields(text) | {f for p in parts.values() for f in _fields(p)} | {p.n for p in parts.values()}
    counts = {text.n} if isinstance(text, Plural) else set()
    counts |= {p.n for p in parts.values()}
    params: dict[str, object] = {name: (OTHER if name in counts else f"<{name}>") for name in names - set(parts)}
    params[counted] = n
    return params


def _expected(code: str, text: Text, params: dict[str, object], lang: str, french) -> str:
    filled = dict(params)
    for name, part in TEXTS[code].parts.items():
        filled[name] = _oracle(code, part, params, lang, french)
    return _oracle(code, text, filled, lang, french)


def test_the_french_catalog_says_that_zero_and_one_are_singular(french):
    assert french.info()["plural-forms"] == "nplurals=2; plural=(n > 1);"
    assert [french.plural(n) for n in COUNTS] == [0, 0, 1, 1]  # gettext's own reading of the header


def test_every_counted_text_is_found():
    """The texts converted for issue 52 (one case per counted text or phrase)."""
    assert len(CASES) >= 39
    assert {code for code, *_ in CASES} >= {
        "BK115", "BK119", "BK123", "BK306", "BK505", "BK620", "BK643", "BK644", "BK645", "BK646", "BK649",
        "BK650", "BK652", "BK701", "BK704", "BK706", "BK800", "BK801", "BK803", "BK811", "BK812", "BK814", "BK819"}


@pytest.mark.parametrize("lang", ["en", "fr"])
@pytest.mark.parametrize("n", COUNTS)
@pytest.mark.parametrize("code, kind, variant, text, part", CASES,
                         ids=[f"{c[0]}-{c[1]}-{c[2] or 'otherwise'}-{c[4] or 'n'}" for c in CASES])
def test_a_counted_text_follows_its_count(code, kind, variant, text, part, n, lang, french):
    counted = TEXTS[code].parts[part].n if part else text.n
    params = _params(code, text, counted, n)
    message = text_message(code, pick(getattr(TEXTS[code], kind), variant), params)
    assert say(message, lang) == _expected(code, text, params, lang, french)


@pytest.mark.parametrize("code, kind, variant, text, part", CASES,
                         ids=[f"{c[0]}-{c[1]}-{c[2] or 'otherwise'}-{c[4] or 'n'}" for c in CASES])
def test_one_and_several_are_two_entries_of_the_catalog(code, kind, variant, text, part, french):
    """English's two forms differ (else the test above could not fail) and the compiled catalog
    holds both French forms (msgstr[0], msgstr[1]; French may write them alike: "fois")."""
    counted = TEXTS[code].parts[part] if part else text
    assert counted.singular != counted.plural
    key = f"{code}\x04{counted.singular}"
    assert french._catalog.get((key, 0)) and french._catalog.get((key, 1)), key  # gettext's own table


def test_a_list_counts_by_its_length():
    assert [count_of(v) for v in ([], ["coude"], ["epaule", "coude"], 5, 2.0, True)] == [0, 1, 2, 5, 2, 1]
    with pytest.raises(TypeError):
        count_of("coude")


HAND_WRITTEN = [
    ("BK119", "more", {"tag": "xacro:property", "more": 1, "path": "bras.urdf"},
     "xacro markup in a plain URDF: <xacro:property> (and 1 more line)",
     "balisage xacro dans un URDF simple : <xacro:property> (et 1 autre ligne)"),
    ("BK306", "fixed", {"robot": "bras", "joints": 1},
     "1 joint, and it is fixed: the robot has nothing to move",
     "1 articulation, et elle est fixe : le robot n'a rien à faire bouger"),
    ("BK645", "", {"names": 0, "positions": 3, "time": 0.5, "count": 1},
     "a JointState names 0 joints but gives 3 positions (t = 0.5 s; 1 such message)",
     "un JointState nomme 0 articulation mais donne 3 positions (t = 0.5 s ; 1 message de ce genre)"),
    ("BK814", "some", {"count": 1, "total": 20, "nodes": ["animation"]},
     "1 of 20 /joint_states messages has header.stamp = 0: robot_state_publisher skips it",
     "1 message /joint_states sur 20 a header.stamp = 0 : robot_state_publisher l'ignore"),
    ("BK812", "sim", {"nodes": ["animation"], "sim": ["animation"], "seconds": 3},
     "'animation' publishes /joint_states but sent nothing in 3 s: 'animation' uses simulated time and "
     "nothing publishes /clock, so its timer never fires",
     "'animation' publie /joint_states mais n'a rien envoyé en 3 s : 'animation' utilise le temps simulé et "
     "rien ne publie /clock, sa minuterie ne se déclenche donc jamais"),
    ("BK620", "", {"joints": ["coude"]},
     "the launch file starts robot_state_publisher but nothing that publishes /joint_states: the joint 'coude' "
     "has no angle",
     "le fichier de lancement démarre robot_state_publisher mais rien qui publie sur /joint_states : "
     "l'articulation 'coude' n'a pas d'angle"),
    ("BK819", "", {"count": 4, "total": 40, "names": 2, "positions": 1},
     "4 of 40 /joint_states messages have 2 names but 1 position: robot_state_publisher ignores them",
     "4 messages /joint_states sur 40 ont 2 noms mais 1 position : robot_state_publisher les ignore"),
]


@pytest.mark.parametrize("code, variant, params, english, french_text", HAND_WRITTEN,
                         ids=[f"{h[0]}-{h[1] or 'otherwise'}" for h in HAND_WRITTEN])
def test_sentences_as_a_person_writes_them(code, variant, params, english, french_text):
    message = text_message(code, pick(TEXTS[code].message, variant), params)
    assert (say(message, "en"), say(message, "fr")) == (english, french_text)


def test_a_real_finding_of_one_fixed_joint_is_singular(tmp_path):
    from bras_kit.validate import validate_path

    urdf = tmp_path / "bras.urdf"
    urdf.write_text('<robot name="bras"><link name="base"/><link name="bras"/>'
                    '<joint name="epaule" type="fixed"><parent link="base"/><child link="bras"/></joint></robot>',
                    encoding="utf-8")
    found = [f for f in validate_path(str(urdf)) if f.code == "BK306"]
    assert [(f.text("en"), f.text("fr")) for f in found] == [(
        "1 joint, and it is fixed: the robot has nothing to move",
        "1 articulation, et elle est fixe : le robot n'a rien à faire bouger")]


# ------------------------------------------------------------ no count beside a fixed plural noun

# words after a field that end in s/x but are no plural noun: verbs, French prepositions
NOT_NOUNS = {"adds", "as", "does", "points", "au-dessus", "aux", "comes", "dans", "dies", "dès", "ends", "exists", "gives", "has",
             "is", "lies", "looks", "mais", "names", "publishes", "reads", "receives", "runs", "sans", "vers",
             "was", "fusionnés", "sous", "des", "/joint_states"}
# fields that hold a measure (a float) or a fixed bound, never a count of things: their unit stays
MEASURES = {
    ("BK214", "angle"): "an angle in radians", ("BK214", "effective"): "an angle in degrees",
    ("BK503", "factor"): "a ratio", ("BK507", "ratio"): "a ratio", ("BK627", "period"): "a period in seconds",
    ("BK627", "ratio"): "a ratio", ("BK652", "period"): "a period in seconds",
    ("BK632", "detail"): "bras-kit's bound MAX_DESCRIPTION_ELEMENTS, never 1",
    # counts a rule only finds at 2 or more: it fires on a rate or on a repeat
    ("BK840", "received"): "the messages of a watch that kept coming, always several",
    ("BK840", "dropped"): "dropped of those kept coming, always several",
    ("BK843", "received"): "a watch's messages, in steps: always several",
    ("BK841", "total"): "the watch's messages (at 20 Hz, several)",
    ("BK844", "count"): "nodes sharing a name: 2 or more by definition",
    ("BK845", "n"): "different robots: 2 or more by definition",
}
# a field, then (an optional adjective and) the next word
CUE = re.compile(r"\{(\w+)(?:[!:][^{}]*)?\}\s+(?:(?:more|moving|such|distinct|other|autres|mobiles|JointState)\s+)?"
                 r"([^\s{}()]+)")


def counted_nouns(code: str, text: str) -> list[str]:
    """``{field} nouns`` spots in ``text``: a field followed by a word ending in s or x."""
    spots = []
    for match in CUE.finditer(text):
        field, word = match.group(1), match.group(2).rstrip(",.:;")
        if len(word) > 1 and word[-1] in "sx" and word not in NOT_NOUNS and (code, field) not in MEASURES:
            spots.append(match.group(0))
    return spots


def test_the_scan_sees_a_count_beside_a_plural_noun():
    assert counted_nouns("BK999", "all {joints} joints are fixed") == ["{joints} joints"]
    assert counted_nouns("BK999", "({count} such messages)") == ["{count} such messages"]
    assert counted_nouns("BK999", "{n} nœuds publient") == ["{n} nœuds"]
    assert counted_nouns("BK999", "{count} travaux") == ["{count} travaux"]
    assert counted_nouns("BK999", "{node} publishes /joint_states at {rate} Hz") == []
    assert counted_nouns("BK214", "{angle} radians") == []


def test_no_plain_text_puts_a_count_beside_a_fixed_plural_noun():
    """Every registered message, hint and title that is no Plural, in English and in French."""
    spots = []
    for code in sorted(TEXTS):
        plain = [text for _kind, _variant, text in _texts(code) if isinstance(text, str)] + [TEXTS[code].title]
        for text in plain:
            for lang in ("en", "fr"):
                spots += [f"{code} ({lang}): {spot}" for spot in counted_nouns(code, raw_text(code, text, lang))]
    assert not spots, "give these a Plural(singular, plural, n):\n" + "\n".join(spots)


def test_the_catalogs_tool_extracts_a_plural_with_its_rule_code(tmp_path):
    """``Plural(...)`` in ``describe`` (a variant's value or a part) becomes msgid + msgid_plural
    with msgctxt = the code, as Babel writes it into validate.po."""
    from babel.messages.pofile import read_po

    from bras_kit.cli import catalogs

    package = tmp_path / "bras_kit" / "validate"
    package.mkdir(parents=True)
    (package / "texts.py").write_text(
        'describe("BK999", title="t", message={"": Plural("{n} joint", "{n} joints", "n"), "x": "plain"},\n'
        '         parts={"such": Plural("{k} message", "{k} messages", "k")}, explanation="e")\n',
        encoding="utf-8")
    found = {(e.context, e.id, e.plural) for e in catalogs.extract_file(package / "texts.py", tmp_path / "bras_kit")}
    assert found == {("BK999", "t", None), ("BK999", "plain", None), ("BK999", "e", None),
                     ("BK999", "{n} joint", "{n} joints"), ("BK999", "{k} message", "{k} messages")}
    with (LOCALE_DIR / "fr" / "LC_MESSAGES" / "validate.po").open("rb") as handle:
        po = read_po(handle)
    entry = po.get("{names} joint", context="BK645")
    assert entry.pluralizable and entry.id == ("{names} joint", "{names} joints")
    assert entry.string == ("{names} articulation", "{names} articulations")


def test_an_entry_that_gains_a_plural_form_is_asked_anew(tmp_path, monkeypatch):
    """A text that was plain and becomes a Plural loses its one-form French (gettext would never
    look it up again) and comes back as msgid_plural with two empty forms to translate."""
    from babel.messages.pofile import read_po

    from bras_kit.cli import catalogs

    folder = tmp_path / "fr" / "LC_MESSAGES"
    folder.mkdir(parents=True)
    (folder / "validate.po").write_text(
        'msgid ""\nmsgstr ""\n"Plural-Forms: nplurals=2; plural=(n > 1);\\n"\n\n'
        'msgctxt "BK999"\nmsgid "{n} joint"\nmsgstr "{n} articulations"\n', encoding="utf-8")
    item = catalogs.Extracted("validate", "{n} joint", "{n} joints", "BK999", "texts.py", 1)
    monkeypatch.setattr(catalogs, "LOCALE_DIR", tmp_path)
    monkeypatch.setattr(catalogs, "extract_all", lambda: [item])
    monkeypatch.setattr(catalogs, "_cli_words", lambda: [])
    untranslated = catalogs.update_catalogs()
    with (folder / "validate.po").open("rb") as handle:
        entry = read_po(handle).get("{n} joint", context="BK999")
    assert entry.id == ("{n} joint", "{n} joints") and entry.string == ("", "")
    assert untranslated["validate"] == [str(entry.id)]
    assert (folder / "validate.mo").exists()
