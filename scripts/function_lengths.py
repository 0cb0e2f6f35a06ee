#!/usr/bin/env python3
"""Function length statistics of cgdem's C++ code (a rough measure, to be re-run after a change).

    scripts/function_lengths.py [--top N] [--root DIR] [FOLDER ...]

FOLDERs default to src, solvers and scaling (relative to the repository root). Prints the
number of functions found, their median and mean length, and the N (default 10) longest
with file, first line and length.

A function's length is its lines from the first line of its signature to its closing
brace, inclusive (blank and comment lines included). Functions are found by brace matching
over the text with comments, string and character literals blanked: a `{` opens a function
body when the text before it (since the last `;`, `{` or `}`) has a parameter list and ends
with `)` or a qualifier (const, override, noexcept, a trailing return type, ...); class,
struct and namespace bodies are entered, control statements and lambdas are counted as part
of the function around them. Macros, templates with braces in their arguments and other
rarities may be missed or cut: the numbers are for comparing a tree with itself.
"""
import argparse
import os
import re
import statistics
import sys

KEYWORDS = {"if", "for", "while", "switch", "catch", "do", "else", "return", "sizeof", "decltype",
            "alignof", "static_assert", "requires", "try"}
SCOPE = re.compile(r"^(?:template\s*<.*>\s*)?(?:namespace|class|struct|union|enum)\b|^extern\s+\"", re.S)
QUALIFIED_END = re.compile(r"(?:\)|\bconst|\boverride|\bfinal|\bnoexcept|\bmutable|->\s*[\w:<>,\s\*&]+)\s*$")


def blank_comments_and_strings(text):
    """The text with comments and literals replaced by spaces (newlines kept)."""
    out, i, n = [], 0, len(text)
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
            out.append("".join(ch if ch == "\n" else " " for ch in text[i:j]))
            i = j
        elif c == 'R' and text.startswith('R"', i) and (i == 0 or not (text[i - 1].isalnum() or text[i - 1] == "_")):
            m = re.match(r'R"([^(\s]*)\(', text[i:])
            if not m:
                out.append(c)
                i += 1
                continue
            end = text.find(")" + m.group(1) + '"', i)
            j = n if end < 0 else end + len(m.group(1)) + 2
            out.append("".join(ch if ch == "\n" else " " for ch in text[i:j]))
            i = j
        elif c in "\"'":
            if c == "'" and i > 0 and text[i - 1].isalnum():  # digit separator 1'000
                out.append(" ")
                i += 1
                continue
            j = i + 1
            while j < n and text[j] != c and text[j] != "\n":
                j += 2 if text[j] == "\\" else 1
            j = min(j + 1, n)
            out.append(c + " " * (j - i - 2) + c if j - i >= 2 else " " * (j - i))
            i = j
        elif c == "#" and (i == 0 or text[i - 1] == "\n"):  # a preprocessor line (with continuations)
            j = i
            while True:
                k = text.find("\n", j)
                if k < 0:
                    k = n
                    break
                if text[k - 1] != "\\":
                    break
                j = k + 1
            out.append(" " * (k - i))
            i = k
        else:
            out.append(c)
            i += 1
    return "".join(out)


def function_name(header):
    """The name before the parameter list of a function header, with its qualifiers."""
    depth, cut = 0, None
    for k, ch in enumerate(header):
        if ch in "<":
            depth += 1
        elif ch == ">" and depth:
            depth -= 1
        elif ch == "(" and depth == 0:
            cut = k
            break
    if cut is None:
        return None
    m = re.search(r"(~?[A-Za-z_][\w:~]*(?:\s*<[^()]*>)?|operator\s*[^\s(]+(?:\(\))?)\s*$", header[:cut])
    return re.sub(r"\s+", "", m.group(1)) if m else None


def functions_of(path):
    """(name, first line, length in lines) of each function defined in a C++ file."""
    with open(path, errors="replace") as f:
        text = blank_comments_and_strings(f.read())
    found = []
    stack = []  # per open brace: ("scope", name) | ("func", name, start line) | ("block",)
    header_start = 0
    i, n = 0, len(text)
    line_at = [0] * (n + 1)
    line = 1
    for k, ch in enumerate(text):
        line_at[k] = line
        if ch == "\n":
            line += 1
    line_at[n] = line
    while i < n:
        ch = text[i]
        if ch == "{":
            header = text[header_start:i].strip()
            in_func = any(s[0] == "func" for s in stack)
            # A brace initializer in a constructor's member list: part of the header.
            if (not in_func and re.search(r"\)\s*:[^:]", header) and re.search(r"[\w>]\s*$", header)
                    and not QUALIFIED_END.search(header)):
                depth, j = 1, i + 1
                while j < n and depth:
                    depth += {"{": 1, "}": -1}.get(text[j], 0)
                    j += 1
                i = j
                continue
            if in_func:
                stack.append(("block",))
            elif SCOPE.search(header):
                m = re.search(r"(?:namespace|class|struct|union)\s+(?:\w+\s+)*?([A-Za-z_]\w*)\s*(?:final\s*)?(?::|$)", header)
                stack.append(("scope", m.group(1) if m else ""))
            else:
                name = function_name(header)
                top = header.split("(")[0]
                words = re.findall(r"[A-Za-z_]\w*", top)
                is_func = (name is not None and QUALIFIED_END.search(header) is not None
                           and not (words and words[-1] in KEYWORDS) and "=" not in top and "[" not in top)
                if is_func:
                    start = header_start + (len(text[header_start:i]) - len(text[header_start:i].lstrip()))
                    scopes = [s[1] for s in stack if s[0] == "scope" and s[1]]
                    cls = [s for s in scopes if s and not s.islower()]
                    qual = (cls[-1] + "::") if cls and "::" not in name else ""
                    stack.append(("func", qual + name, line_at[start]))
                else:
                    stack.append(("block",))
            header_start = i + 1
        elif ch == "}":
            if stack:
                top = stack.pop()
                if top[0] == "func":
                    found.append((top[1], top[2], line_at[i] - top[2] + 1))
            header_start = i + 1
        elif ch == ";":
            header_start = i + 1
        i += 1
    return found


def main(argv):
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("folders", nargs="*", default=["src", "solvers", "scaling"])
    ap.add_argument("--top", type=int, default=10)
    ap.add_argument("--root", default=os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
    a = ap.parse_args(argv[1:])
    rows = []
    for folder in a.folders:
        for dirpath, _, files in os.walk(os.path.join(a.root, folder)):
            for name in sorted(files):
                if name.endswith((".cpp", ".hpp", ".h", ".cc")):
                    path = os.path.join(dirpath, name)
                    rel = os.path.relpath(path, a.root)
                    rows += [(length, rel, first, fn) for fn, first, length in functions_of(path)]
    if not rows:
        print("no functions found")
        return 1
    lengths = [r[0] for r in rows]
    print(f"{len(rows)} functions in {', '.join(a.folders)}: median {statistics.median(lengths):g} lines, "
          f"mean {statistics.mean(lengths):.1f}")
    print(f"the {a.top} longest:")
    for length, rel, first, fn in sorted(rows, key=lambda r: (-r[0], r[1], r[2]))[:a.top]:
        print(f"  {length:5d}  {fn}  ({rel}:{first})")
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv))
