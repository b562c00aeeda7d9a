"""The README's system packages, rendered from system-packages.txt (the one list; .ci/run reads it too).

    python tools/system_packages.py            print the README's block
    python tools/system_packages.py --write    rewrite that block in README.md
    python tools/system_packages.py --column debian-12    the packages of one platform (.ci/run's form)

tests/project/test_system_packages.py fails when README.md does not hold the block as rendered here.
"""

from __future__ import annotations

import sys
from dataclasses import dataclass
from pathlib import Path

ROOT = Path(__file__).resolve().parent.parent
LIST = ROOT / "system-packages.txt"
README = ROOT / "README.md"
PLATFORMS = {"debian-12": "Debian 12", "ubuntu-24.04": "Ubuntu 24.04"}
ABSENT = "-"
BEGIN = "<!-- system packages: rendered from system-packages.txt by `python tools/system_packages.py --write` -->"
END = "<!-- end of the system packages -->"


@dataclass(frozen=True)
class SystemPackage:
    names: dict[str, str]  # platform -> the package's name there, or "-"
    why: str


def read_list(path: Path = LIST) -> list[SystemPackage]:
    out = []
    for number, line in enumerate(path.read_text(encoding="utf-8").splitlines(), 1):
        if not line.strip() or line.lstrip().startswith("#"):
            continue
        parts = line.split(None, len(PLATFORMS))
        if len(parts) != len(PLATFORMS) + 1:
            raise SystemExit(f"{path}:{number}: expected {len(PLATFORMS)} package names and what needs it")
        out.append(SystemPackage(dict(zip(PLATFORMS, parts)), parts[-1]))
    return out


def column(platform: str, packages: list[SystemPackage] | None = None) -> list[str]:
    """The packages to install on ``platform`` (a key of :data:`PLATFORMS`)."""
    return [p.names[platform] for p in (read_list() if packages is None else packages)
            if p.names[platform] != ABSENT]


def block(packages: list[SystemPackage] | None = None) -> str:
    """The README's text between :data:`BEGIN` and :data:`END`, both included."""
    packages = read_list() if packages is None else packages
    lines = [BEGIN, ""]
    for platform, title in PLATFORMS.items():
        lines += [f"{title}:", "", "```console",
                  "sudo apt-get update && sudo apt-get install -y " + " ".join(column(platform, packages)),
                  "```", ""]
    lines += ["| " + " | ".join(PLATFORMS.values()) + " | what needs it |",
              "|" + "---|" * (len(PLATFORMS) + 1)]
    for package in packages:
        names = [f"`{n}`" if n != ABSENT else "none" for n in package.names.values()]
        lines.append("| " + " | ".join(names) + f" | {package.why} |")
    lines += ["", END]
    return "\n".join(lines)


def write_readme() -> bool:
    """Put the rendered block in README.md (between its markers); True when it changed."""
    text = README.read_text(encoding="utf-8")
    start, end = text.index(BEGIN), text.index(END) + len(END)
    new = text[:start] + block() + text[end:]
    if new != text:
        README.write_text(new, encoding="utf-8")
    return new != text


def main(argv: list[str]) -> int:
    if argv[:1] == ["--write"]:
        print("README.md " + ("updated" if write_readme() else "already current"))
    elif argv[:1] == ["--column"] and len(argv) == 2 and argv[1] in PLATFORMS:
        print(" ".join(column(argv[1])))
    elif not argv:
        print(block())
    else:
        print(__doc__, file=sys.stderr)
        return 2
    return 0


if __name__ == "__main__":
    raise SystemExit(main(sys.argv[1:]))
