"""The words a page shows a person: its text nodes, and the titles, labels and placeholders of its
elements (what a tooltip or a screen reader says). Shared by the viewer's language tests."""

from __future__ import annotations

from typing import Any

WORDS_SCRIPT = """() => {
    const out = [];
    const walker = document.createTreeWalker(document.body, NodeFilter.SHOW_TEXT);
    while (walker.nextNode()) out.push(walker.currentNode.nodeValue.trim());
    for (const e of document.querySelectorAll("[title],[aria-label],[placeholder]"))
        for (const name of ["title", "aria-label", "placeholder"])
            if (e.hasAttribute(name)) out.push(e.getAttribute(name).trim());
    return out;
}"""


def page_words(page: Any) -> list[str]:
    """Every word group a Playwright ``page`` shows, in document order."""
    return page.evaluate(WORDS_SCRIPT)  # type: ignore[no-any-return]
