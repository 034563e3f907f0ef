#!/usr/bin/env python3
"""House limits: no source file over 600 lines, no function over 80 lines (outside tests).

Usage: scripts/check_sizes.py [--list N] [ROOT]
Prints each violation as `path:line: what` and exits 1 if there is any that is not listed in
EXCEPTIONS below (each with the reason it stays). --list N prints every function longer than N
lines instead (for finding the next candidates).

Functions are found by brace matching on the source with comments, strings and character
literals blanked: a `{` that opens at namespace or class depth and follows a `)` (optionally
trailed by const/noexcept/override/-> type/member initialisers) starts a function body. Lambdas and
local classes count towards the function that holds them.
"""
import os
import re
import sys

MAX_FILE_LINES = 600
MAX_FUNCTION_LINES = 80
SOURCE_DIRS = ["anim", "runtime", "bake", "platform", "tools", "bench"]
EXTENSIONS = (".cpp", ".h", ".c")
# path (relative to the root) or path:function -> why it stays.
EXCEPTIONS = {
    "runtime/refinement_pattern.inc": "generated data table (tools/make_refinement_pattern.cpp)",
}


def blank_comments_and_strings(text):
    """Replaces comments, string and char literals by spaces, keeping newlines."""
    out = []
    i, n = 0, len(text)
    while i < n:
        c = text[i]
        if text.startswith("//", i):
            j = text.find("\n", i)
            j = n if j < 0 else j
            out.append(" " * (j - i))
            i = j
        elif text.startswith("/*", i):
            j = text.find("*/", i + 2)
            j = n if j < 0 else j + 2
            out.append(re.sub(r"[^\n]", " ", text[i:j]))
            i = j
        elif c == 'R' and text.startswith('R"', i):
            m = re.match(r'R"([^(]*)\(', text[i:])
            if not m:
                out.append(c)
                i += 1
                continue
            end = ")" + m.group(1) + '"'
            j = text.find(end, i + m.end())
            j = n if j < 0 else j + len(end)
            out.append(re.sub(r"[^\n]", " ", text[i:j]))
            i = j
        elif c in "\"'":
            if c == "'" and i > 0 and (text[i - 1].isalnum()) and text[i - 1] not in "uULR8":
                out.append(c)  # digit separator 1'000
                i += 1
                continue
            j = i + 1
            while j < n and text[j] != c and text[j] != "\n":
                j += 2 if text[j] == "\\" else 1
            j = min(j + 1, n)
            out.append(" " * (j - i))
            i = j
        else:
            out.append(c)
            i += 1
    return "".join(out)


HEADER_TAIL = re.compile(
    r"\)\s*(const|noexcept(\([^)]*\))?|override|final|mutable|->\s*[\w:<>,\s\*&]+|\s)*"
    r"(:\s*[\w:]+\s*[\({][^;]*?)?\s*$",
    re.S,
)
NAME_BEFORE_PAREN = re.compile(r"([~\w:]+|operator\s*[^\s(]+)\s*$")
NOT_FUNCTIONS = {"if", "for", "while", "switch", "catch", "return", "sizeof", "decltype"}


def function_name(header):
    """Name of the function whose parameter list ends `header`, or None."""
    depth = 0
    for k in range(len(header) - 1, -1, -1):
        ch = header[k]
        if ch == ")":
            depth += 1
        elif ch == "(":
            depth -= 1
            if depth == 0:
                m = NAME_BEFORE_PAREN.search(header[:k])
                if not m:
                    return None
                name = m.group(1)
                if name.split("::")[-1] in NOT_FUNCTIONS:
                    return None
                return name
    return None


def functions(text):
    """Yields (name, first line, line count) of every function body in `text`."""
    code = blank_comments_and_strings(text)
    stack = []  # for each open brace: "scope" (namespace/class/extern) or "body"/"inner"
    stmt_start = 0
    for i, ch in enumerate(code):
        if ch == "{":
            in_body = any(s[0] in ("body", "inner") for s in stack)
            if in_body:
                stack.append(("inner", i))
            else:
                header = code[stmt_start:i]
                tail_ok = HEADER_TAIL.search(header) is not None
                name = function_name(header[: HEADER_TAIL.search(header).start() + 1]) if tail_ok else None
                if name and not re.search(r"\b(namespace|class|struct|union|enum)\b[^(]*$", header):
                    stack.append(("body", i, name))
                else:
                    stack.append(("scope", i))
            stmt_start = i + 1
        elif ch == "}":
            if stack:
                top = stack.pop()
                if top[0] == "body":
                    first = code.count("\n", 0, top[1]) + 1
                    last = code.count("\n", 0, i) + 1
                    yield top[2], first, last - first + 1
            stmt_start = i + 1
        elif ch == ";":
            if not any(s[0] in ("body", "inner") for s in stack):
                stmt_start = i + 1
        elif ch == "#" and (i == 0 or code[i - 1] == "\n"):
            stmt_start = i  # preprocessor lines end a declaration
            j = code.find("\n", i)
            if j > 0:
                stmt_start = j + 1


def main():
    args = sys.argv[1:]
    list_over = None
    if args[:1] == ["--list"]:
        list_over = int(args[1])
        args = args[2:]
    root = args[0] if args else os.path.join(os.path.dirname(os.path.abspath(__file__)), "..")
    problems, excepted = [], []
    for d in SOURCE_DIRS:
        for base, _, files in os.walk(os.path.join(root, d)):
            for f in sorted(files):
                if not f.endswith(EXTENSIONS + (".inc",)):
                    continue
                path = os.path.join(base, f)
                rel = os.path.relpath(path, root)
                with open(path, encoding="utf-8", errors="replace") as fh:
                    text = fh.read()
                lines = text.count("\n")
                if lines > MAX_FILE_LINES and list_over is None:
                    (excepted if rel in EXCEPTIONS else problems).append(
                        f"{rel}:1: {lines} lines (limit {MAX_FILE_LINES})")
                if f.endswith(".inc"):
                    continue
                for name, first, count in functions(text):
                    limit = MAX_FUNCTION_LINES if list_over is None else list_over
                    if count > limit:
                        msg = f"{rel}:{first}: {name}() is {count} lines (limit {limit})"
                        key = f"{rel}:{name}"
                        (excepted if key in EXCEPTIONS and list_over is None else problems).append(msg)
    for p in excepted:
        key = p.split(":")[0]
        print(f"excepted  {p}  -- {EXCEPTIONS.get(key, '')}")
    for p in problems:
        print(p)
    if list_over is not None:
        return 0
    return 1 if problems else 0


if __name__ == "__main__":
    sys.exit(main())
