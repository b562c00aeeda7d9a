"""Safe XML reading with source lines.

Only expat is used, with a handler that stops at the first DTD, entity declaration or
external entity: nothing is ever expanded or fetched (no billion laughs, no XXE).
The result is a small tree of :class:`Node` objects that remember their line.
"""

from __future__ import annotations

import os
import re
import stat
import xml.parsers.expat
from collections.abc import Iterator
from dataclasses import dataclass, field

from ..core.errors import BrasKitError, XMLSafetyError, XMLSyntaxError, os_reason
from ..core.message import M, Message

_DTD_HINT = M("remove the <!DOCTYPE ...> block: URDF files never need one")
# what the XML declared that bras-kit refuses, by kind (the validator words BK101 by kind)
_REFUSED = {
    "dtd": M("a DTD (<!DOCTYPE>)"),
    "attlist": M("an attribute list declaration (<!ATTLIST>)"),
    "entity": M("an entity declaration (<!ENTITY>)"),
    "external": M("an external entity"),
}


@dataclass
class Node:
    """One XML element: tag, attributes, children, text and the line it starts on."""

    tag: str
    attrib: dict[str, str]
    line: int
    children: list[Node] = field(default_factory=list)
    text: str = ""
    late_declaration: int | None = None  # root only: line of an <?xml ?> that did not come first
    late_declaration_after: str | None = None  # what came before it: "tab", "space" or "line"

    def find(self, tag: str) -> Node | None:
        for child in self.children:
            if child.tag == tag:
                return child
        return None

    def findall(self, tag: str) -> list[Node]:
        return [child for child in self.children if child.tag == tag]

    def get(self, key: str, default: str | None = None) -> str | None:
        return self.attrib.get(key, default)

    def iter(self) -> Iterator[Node]:
        """All nodes below and including this one, depth first, without recursion."""
        stack = [self]
        while stack:
            node = stack.pop()
            yield node
            stack.extend(reversed(node.children))


class _Refused(Exception):
    def __init__(self, what: str, line: int) -> None:
        super().__init__(what)
        self.what = what
        self.line = line


def parse_xml(data: bytes | str, path: str | None = None) -> Node:
    """Parse XML text into a :class:`Node` tree, refusing DTDs and entities.

    Raises :class:`XMLSafetyError` or :class:`XMLSyntaxError` with the path and line.
    """
    if isinstance(data, str):
        data = data.encode("utf-8")
    late_after = _before_declaration(data)
    data, late_declaration = _blank_late_declaration(data)
    parser = xml.parsers.expat.ParserCreate()
    parser.buffer_text = True  # one text callback per run of text, not one per line
    root_holder: list[Node] = []
    stack: list[Node] = []

    def refuse(kind: str) -> None:
        raise _Refused(kind, parser.CurrentLineNumber)

    def start(tag: str, attrs: dict[str, str]) -> None:
        node = Node(tag, dict(attrs), parser.CurrentLineNumber)
        if stack:
            stack[-1].children.append(node)
        else:
            root_holder.append(node)
        stack.append(node)

    def end(tag: str) -> None:
        stack.pop()

    def chars(text: str) -> None:
        if stack:
            stack[-1].text += text

    parser.StartElementHandler = start
    parser.EndElementHandler = end
    parser.CharacterDataHandler = chars
    def doctype(name: str, system_id: str | None, public_id: str | None, internal_subset: int) -> None:
        if system_id or public_id:  # <!DOCTYPE robot> alone names the root and is harmless
            refuse("dtd")

    parser.StartDoctypeDeclHandler = doctype
    parser.AttlistDeclHandler = lambda *a: refuse("attlist")
    parser.EntityDeclHandler = lambda *a: refuse("entity")
    def refuse_external(*args: object) -> int:
        refuse("external")
        return 0

    parser.ExternalEntityRefHandler = refuse_external
    parser.SetParamEntityParsing(xml.parsers.expat.XML_PARAM_ENTITY_PARSING_NEVER)
    try:
        parser.Parse(data, True)
    except _Refused as exc:
        refused = XMLSafetyError(
            M("refused: the XML contains {what}; bras-kit never expands entities or DTDs", what=_REFUSED[exc.what]),
            path=path,
            line=exc.line,
            hint=_DTD_HINT,
        )
        refused.kind = exc.what
        raise refused from None
    except xml.parsers.expat.ExpatError as exc:
        reason = xml.parsers.expat.ErrorString(exc.code)
        if "undefined entity" in reason:
            refused = XMLSafetyError(
                M("refused: undefined entity at column {column}; entities are not expanded", column=exc.offset + 1),
                path=path,
                line=exc.lineno,
                hint=M("write the character itself instead of an &entity; reference"),
            )
            refused.kind = "undefined"
            raise refused from None
        pasted = _pasted_character(data, exc.lineno)
        if pasted is not None:
            detail, hint = pasted
            line = exc.lineno
        else:
            detail, line = _syntax_detail(exc, reason, stack, data)
            hint = M("check the tag on this line is closed and its quotes match")
        error = XMLSyntaxError(M("not well-formed XML: {detail}", detail=detail), path=path, line=line, hint=hint)
        error.detail = detail
        error.fix = hint if pasted is not None else None
        raise error from None
    if not root_holder:
        raise XMLSyntaxError(M("the file holds no XML element"), path=path, line=1)
    root_holder[0].late_declaration = late_declaration
    root_holder[0].late_declaration_after = late_after if late_declaration is not None else None
    return root_holder[0]


def _opening(node: Node) -> str:
    """``<link name="bras">``: an element as the learner wrote its opening tag (its name only)."""
    name = node.attrib.get("name")
    return f'<{node.tag} name="{name}">' if name is not None else f"<{node.tag}>"


# expat's fixed messages (xmlparse.c), each worded as data so that it can be translated
_EXPAT_WORDS = {
    "not well-formed (invalid token)": M("a character that cannot start or continue a tag here "
                                         "(an unquoted value, a stray '<' or '&'?)"),
    "unclosed token": M("a tag or a quoted value is not finished"),
    "junk after document element": M("text or a second element after the closing tag of the root element"),
    "duplicate attribute": M("the same attribute is written twice in one tag"),
    "syntax error": M("syntax error"),
    "no element found": M("the file ends before its elements are closed"),
    "unbound prefix": M("a prefix (name:) is used without its xmlns declaration"),
    "XML or text declaration not at start of entity": M("the <?xml ...?> declaration is not at the very start of the file"),
    "unclosed CDATA section": M("a <![CDATA[ section is never closed"),
    "partial character": M("the file ends in the middle of a character"),
    "reference to invalid character number": M("a &#...; reference names a character XML does not allow"),
    "XML declaration not well-formed": M("the <?xml ...?> declaration is not well-formed"),
    "mismatched tag": M("a closing tag does not match the element it closes"),
}


def _syntax_detail(exc: xml.parsers.expat.ExpatError, reason: str, stack: list[Node],
                   data: bytes) -> tuple[Message, int]:
    """What is wrong, as a message, and the line to show: the element left open (and its
    opening line) when a closing tag does not match or the file ends, else expat's reason."""
    column = exc.offset + 1
    stopped = exc.lineno
    if reason == "mismatched tag" and stack:
        lines = data.split(b"\n")
        text = lines[stopped - 1][exc.offset:].decode("utf-8", "replace") if stopped - 1 < len(lines) else ""
        found = re.match(r"(?:</)?\s*([^\s>/]+)", text)  # expat's column points at the closing tag's name
        closing = found.group(1) if found else "?"
        innermost = stack[-1]
        if any(node.tag == closing for node in stack[:-1]):
            return (M("the tag {element} opened on line {opened} is never closed: the reader met </{closing}> "
                      "on line {stopped} while {element} was still open",
                      element=_opening(innermost), opened=innermost.line, closing=closing, stopped=stopped),
                    innermost.line)
        return (M("the closing tag </{closing}> on line {stopped} does not match {element} opened on line {opened}",
                  closing=closing, stopped=stopped, element=_opening(innermost), opened=innermost.line), stopped)
    if reason == "no element found" and stack:
        innermost = stack[-1]
        return (M("the tag {element} opened on line {opened} is never closed: the file ends on line {stopped}",
                  element=_opening(innermost), opened=innermost.line, stopped=stopped), innermost.line)
    words = _EXPAT_WORDS.get(reason)
    if words is None:
        words = M("the XML reader says \"{reason}\"", reason=reason)
    return M("{what} (line {line}, column {column})", what=words, line=stopped, column=column), stopped


# Characters a word processor, a chat or a web page pastes where XML wants plain ASCII punctuation:
# expat stops on them with "invalid token", which says nothing of the character itself.
_CURLY_QUOTES = "\u201c\u201d\u201e\u201f\u2018\u2019\u201a\u201b\u00ab\u00bb\u2039\u203a\u2033"
_ODD_SPACES = "\u00a0\u202f\u2007\u2009\u2002\u2003\u3000"
_INVISIBLE = "\ufeff\u200b\u200c\u200d\u2060"


def _pasted_character(data: bytes, line: int) -> tuple[Message, Message] | None:
    """When the line where the XML reader stopped holds a curly quote, a non-breaking space or an
    invisible mark (a byte order mark, a zero-width space): what it is, where, and the fix."""
    lines = data.split(b"\n")
    if not 0 < line <= len(lines):
        return None
    text = lines[line - 1].decode("utf-8", "replace")
    for column, char in enumerate(text, start=1):
        if char not in _CURLY_QUOTES + _ODD_SPACES + _INVISIBLE:
            continue
        code = f"U+{ord(char):04X}"  # the Unicode name is English: the message says what it is
        if char in _CURLY_QUOTES:
            straight = "'" if char in "\u2018\u2019\u201a\u201b\u2039\u203a" else '"'
            curly = " ".join(dict.fromkeys(c for c in text if c in _CURLY_QUOTES))
            return (M("the typographic quote {char} ({code}) at column {column}, as a word processor or a chat "
                      "pastes it: XML only takes straight quotes around a value", char=char, code=code, column=column),
                    M("replace {curly} on this line with {straight}, and paste code into a code editor, "
                      "not a word processor", curly=curly, straight=straight))
        if char in _ODD_SPACES:
            return (M("a non-breaking space ({code}) at column {column}: it looks like a space, but XML does not "
                      "take it between a tag's name and its attributes", code=code, column=column),
                    M("delete the space at column {column} and type an ordinary one", column=column))
        if char == "\ufeff":
            what = M("a byte order mark ({code}) at column {column}: an invisible mark that only the very start "
                     "of a file may hold, left here by a copy and paste", code=code, column=column)
        else:
            what = M("an invisible character ({code}) at column {column}, left by a copy and paste", code=code,
                     column=column)
        return (what,
                M("delete the invisible character just before '{after}' (in most editors: put the cursor before "
                  "'{after}', then press Backspace)", after=_token(text[column:])))
    return None


def _token(text: str) -> str:
    found = re.match(r"\s*([^\s\"'=>]{1,12})", text)
    return found.group(1) if found else text[:1]


_LATE_DECLARATION = re.compile(rb"\A(\xef\xbb\xbf)?(\s+)(<\?xml\b[^>]*\?>)")


def _before_declaration(data: bytes) -> str | None:
    """What stands before a late ``<?xml ...?>``: ``"tab"`` (pasted from an indented listing),
    ``"line"`` (blank lines) or ``"space"``; None when the declaration comes first."""
    match = _LATE_DECLARATION.match(data[:4096])
    if match is None:
        return None
    blank = match.group(2)
    return "tab" if b"\t" in blank else "line" if b"\n" in blank else "space"


def _blank_late_declaration(data: bytes) -> tuple[bytes, int | None]:
    """Blank an ``<?xml ...?>`` declaration that follows blank lines or spaces (expat refuses it;
    urdfdom and pybullet read such files). Returns the data, same length and lines, and the
    declaration's line, or None when there was nothing to blank."""
    match = _LATE_DECLARATION.match(data[:4096])
    if match is None:
        return data, None
    start, end = match.span(3)
    line = data[:start].count(b"\n") + 1
    return data[:start] + b" " * (end - start) + data[end:], line


MAX_READ_BYTES = 256 << 20


def read_bytes(path: str | os.PathLike[str], roots: tuple[str, ...] | None = None) -> bytes:
    """A file's bytes; a missing or unreadable file is a :class:`BrasKitError` naming it. With
    ``roots``, read through the one reader (:func:`bras_kit.model.xacro_files.read_beneath`)."""
    path = os.fspath(path)
    if roots is not None and path != "-":
        from .xacro_files import read_beneath

        if os.path.isdir(path):
            raise BrasKitError(M("{path} is a folder, not a file", path=path))
        return read_beneath(path, roots, MAX_READ_BYTES)
    if path == "-":
        import sys

        data = sys.stdin.buffer.read(MAX_READ_BYTES + 1)
        if len(data) > MAX_READ_BYTES:
            raise BrasKitError(M("refused to read standard input: more than {mib} MiB", mib=MAX_READ_BYTES >> 20))
        return data
    try:
        info = os.stat(path)
        if not stat.S_ISREG(info.st_mode) and not stat.S_ISDIR(info.st_mode):
            raise BrasKitError(M("refused to read {path}: it is not a regular file (a device, pipe or socket)",
                                 path=path), hint=M("give the path of a .urdf or .xacro file"))
        if info.st_size > MAX_READ_BYTES:
            raise BrasKitError(M("refused to read {path}: {size} bytes is more than the {mib} MiB a robot "
                                 "description may have", path=path, size=info.st_size, mib=MAX_READ_BYTES >> 20))
        with open(path, "rb") as handle:
            return handle.read()
    except FileNotFoundError:
        raise BrasKitError(M("no such file: {path}", path=path), hint=M("check the path and spelling")) from None
    except IsADirectoryError:
        raise BrasKitError(M("{path} is a folder, not a file", path=path)) from None
    except OSError as exc:
        raise BrasKitError(M("cannot read {path}: {reason}", path=path, reason=os_reason(exc))) from None


def read_xml(path: str | os.PathLike[str], roots: tuple[str, ...] | None = None) -> Node:
    """Read and safely parse an XML file; a missing or unreadable file is a :class:`BrasKitError`."""
    return parse_xml(read_bytes(path, roots), path=os.fspath(path))


def check_xml_safe(data: bytes | str, path: str | None = None) -> None:
    """Raise unless ``data`` is well-formed XML with no DTD or entity (used before handing files to xacro)."""
    parse_xml(data, path=path)
