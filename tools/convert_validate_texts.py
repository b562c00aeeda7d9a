"""One-off (issue 21): move the validator's rule texts from the messages_*.py dict tables to
gettext. Writes the English into bras_kit/validate/texts.py and bras_kit/validate/package/texts.py
(``describe(...)`` calls) and, with ``--po``, fills the French msgstr of validate.po from the old
French tables (msgctxt = rule code). Run from the repository root:

    python tools/convert_validate_texts.py --texts
    python -m bras_kit.core.i18n update
    python tools/convert_validate_texts.py --po
    python -m bras_kit.core.i18n compile
"""

from __future__ import annotations

import sys
from pathlib import Path

ROOT = Path(__file__).resolve().parent.parent
sys.path.insert(0, str(ROOT))

FAMILY_HEADERS = {
    "BK1": "BK1xx structure", "BK2": "BK2xx joints", "BK3": "BK3xx the tutorial's pitfalls",
    "BK4": "BK4xx geometry", "BK5": "BK5xx inertia", "BK6": "BK6xx the ROS 2 package",
}


def _literal(text: str, indent: str) -> str:
    if "\n" in text and '"""' not in text and "\\" not in text and not text.endswith('"'):
        return '"""\\\n' + text + '"""'
    if '"' not in text and "\\" not in text and "\n" not in text:
        return '"' + text + '"'
    return repr(text)


def _value(value, indent: str) -> str:
    if isinstance(value, str):
        return _literal(value, indent)
    inner = "".join(f"{indent}    {_literal(k, indent)}: {_literal(v, indent + '    ')},\n" for k, v in value.items())
    return "{\n" + inner + indent + "}"


def write_texts(tables, path: Path, doc: str, import_line: str) -> None:
    out = [f'"""{doc}"""', "", "from __future__ import annotations", "", import_line, ""]
    family = None
    for code, text in tables.items():
        if code[:3] != family:
            family = code[:3]
            out += ["", f"# {'-' * 66} {FAMILY_HEADERS[family]}", ""]
        out.append("describe(")
        out.append(f"    \"{code}\",")
        out.append(f"    title={_literal(text.title, '    ')},")
        out.append(f"    message={_value(text.message, '    ')},")
        if text.hint:
            out.append(f"    hint={_value(text.hint, '    ')},")
        out.append(f"    explanation={_literal(text.explanation, '    ')},")
        out.append(")")
    path.write_text("\n".join(out) + "\n", encoding="utf-8")


def texts() -> None:
    from bras_kit.validate import messages_en
    from bras_kit.validate.package import messages_en as package_en

    urdf = {k: v for k, v in messages_en.RULE_TEXTS.items() if not k.startswith("BK6")}
    write_texts(urdf, ROOT / "bras_kit/validate/texts.py",
                "The English words of the URDF and xacro rules (BK1xx-BK5xx): title, message, hint and the\n"
                "explanation ``bras-kit explain CODE`` shows. French: ``locale/fr/LC_MESSAGES/validate.po``\n"
                "(msgctxt = the rule code).", "from .registry import describe")
    write_texts(package_en.RULE_TEXTS, ROOT / "bras_kit/validate/package/texts.py",
                "The English words of the package rules (BK6xx). French: ``validate.po`` (msgctxt = code).",
                "from ..registry import describe")


def _pairs(en, fr):
    if isinstance(en, str):
        fr_value = fr if isinstance(fr, str) else fr[""]
        return [(en, fr_value)] if en else []
    return [(en[k], fr[k] if isinstance(fr, dict) else fr) for k in en]


def po() -> None:
    from babel.messages.pofile import read_po, write_po

    from bras_kit.validate import messages_en, messages_fr
    from bras_kit.validate.package import messages_en as package_en
    from bras_kit.validate.package import messages_fr as package_fr

    en_all = {**messages_en.RULE_TEXTS, **package_en.RULE_TEXTS}
    fr_all = {**messages_fr.RULE_TEXTS, **package_fr.RULE_TEXTS}
    french: dict[tuple[str, str | None], str] = {}
    for code, en in en_all.items():
        fr = fr_all[code]
        for part in ("title", "message", "hint", "explanation"):
            for english, translated in _pairs(getattr(en, part), getattr(fr, part)):
                french[(english, code)] = translated
    ui = messages_fr.UI
    for key in ("error", "warning", "info"):
        french[(key, None)] = ui[key]
    for family in ("structure", "joints", "pitfalls", "geometry", "inertia", "package"):
        french[(messages_en.UI[f"family_{family}"], None)] = ui[f"family_{family}"]
    french[("Family: {family}", None)] = ui["family"] + ui["colon"] + "{family}"
    french[("Skip it with: bras-kit validate --ignore {code}", None)] = ui["skip"]
    french[("hint: {hint}", None)] = ui["hint"] + ui["colon"] + "{hint}"
    french[("{checked}: {counts}.", None)] = "{checked}" + ui["colon"] + "{counts}."
    french[("{checked}: no problems found.", None)] = "{checked}" + ui["colon"] + ui["clean"] + "."
    plurals = {messages_en.UI[f"{key}_one"]: (ui[f"{key}_one"], ui[f"{key}_many"])
               for key in ("checked", "unreadable", "errors", "warnings", "infos")}
    path = ROOT / "bras_kit/locale/fr/LC_MESSAGES/validate.po"
    with path.open("rb") as handle:
        catalog = read_po(handle, locale="fr")
    filled = 0
    for message in catalog:
        if isinstance(message.id, tuple) and message.id[0] in plurals and not all(message.string):
            message.string = plurals[message.id[0]]
            filled += 1
        elif message.id and not message.string and (message.id, message.context) in french:
            message.string = french[(message.id, message.context)]
            filled += 1
    with path.open("wb") as handle:
        write_po(handle, catalog, width=0, omit_header=False, sort_output=False)
    print(f"{filled} entries filled")


if __name__ == "__main__":
    {"--texts": texts, "--po": po}[sys.argv[1]]()
