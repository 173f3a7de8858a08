"""No function of src/ over 80 lines without a reason written beside it.

Scans src/**/*.cpp and src/**/*.hpp for function bodies and reports every function whose body,
from the line of its opening brace to the line of its closing brace (both counted), is longer
than 80 lines. A long function is accepted when a comment in the comment block just above its
signature (or on the signature's own lines) carries the marker `long-function:` and a reason:
    // long-function: one switch over the 14 job-key kinds; splitting scatters the table
The scanner matches braces in the code with comments, string and character literals (raw strings
included) and preprocessor lines blanked out. Namespace, class, struct, union and enum bodies are
scopes, not functions; a lambda or a local class inside a function is part of that function; a
lambda at namespace or class scope counts as a function of its own.

Usage: check_function_length.py [REPO_ROOT] [--self-test]
  exit 1 listing the offenders, 0 when there are none; a one-line count either way.
"""
import glob
import os
import re
import sys

LIMIT = 80
MARKER = re.compile(r"long-function:\s*\S")


def blank_non_code(text):
    """Returns (code, comments): code is text with comments, literal contents and preprocessor
    lines replaced by spaces (newlines kept, so offsets keep their lines); comments maps a line
    number (1-based) to the comment text found on it."""
    out = list(text)
    comments = {}
    n = len(text)
    i = 0
    line = 1
    at_line_start = True  # only blanks seen since the last newline

    def literal_end(i, quote):
        """Just past the string or character literal opened by the quote at i (escapes skipped;
        an unclosed one ends at its line's end)."""
        end = i + 1
        while end < n and text[end] != quote and text[end] != "\n":
            end += 2 if text[end] == "\\" else 1
        return min(end + 1, n)

    def blank(a, b):
        nonlocal line
        for k in range(a, b):
            if out[k] == "\n":
                line += 1
            else:
                out[k] = " "

    def note(a, b, first_line):
        for k, part in enumerate(text[a:b].split("\n")):
            comments[first_line + k] = comments.get(first_line + k, "") + part

    while i < n:
        c = text[i]
        if c == "\n":
            line += 1
            at_line_start = True
            i += 1
            continue
        if c in " \t\r\f\v":
            i += 1
            continue
        if at_line_start and c == "#":
            # A preprocessor line, with its continuations.
            j = i
            while j < n and text[j] != "\n":
                if text[j] == "\\" and j + 1 < n and text[j + 1] == "\n":
                    j += 2
                    continue
                if text.startswith("/*", j) or text.startswith("//", j):
                    break
                j += 1
            blank(i, j)
            i = j
            continue
        at_line_start = False
        if text.startswith("//", i):
            j = text.find("\n", i)
            j = n if j < 0 else j
            note(i, j, line)
            blank(i, j)
            i = j
            continue
        if text.startswith("/*", i):
            j = text.find("*/", i + 2)
            j = n if j < 0 else j + 2
            note(i, j, line)
            blank(i, j)
            i = j
            continue
        if c == '"':
            m = re.match(r'R"([^()\\ ]{0,16})\(', text[i - 1:i + 20]) if i > 0 else None
            if m and text[i - 1] == "R":
                end = text.find(")" + m.group(1) + '"', i)
                end = n if end < 0 else end + len(m.group(1)) + 2
            else:
                end = literal_end(i, '"')
            blank(i + 1, end - 1)
            i = end
            continue
        if c == "'":
            # A digit separator (1'000'000) or a character literal.
            k = i
            while k > 0 and (text[k - 1].isalnum() or text[k - 1] in "_."):
                k -= 1
            if k < i and text[k].isdigit():
                i += 1
                continue
            end = literal_end(i, "'")
            blank(i + 1, end - 1)
            i = end
            continue
        i += 1
    return "".join(out), comments


def collapse(s):
    """s with every outermost (...) group written () and {...} group written {}."""
    out = []
    depth = 0
    for c in s:
        if c in "({":
            if depth == 0:
                out.append(c)
            depth += 1
        elif c in ")}":
            depth -= 1
            if depth == 0:
                out.append(c)
        elif depth == 0:
            out.append(c)
    return "".join(out)


def strip_template_prefix(h):
    while True:
        m = re.match(r"template\s*<", h)
        if not m:
            return h
        depth = 0
        for k in range(m.end() - 1, len(h)):
            if h[k] == "<":
                depth += 1
            elif h[k] == ">":
                depth -= 1
                if depth == 0:
                    h = h[k + 1:].lstrip()
                    break
        else:
            return h


QUALIFIERS = r"(?:\s*(?:const|volatile|noexcept\s*(?:\(\))?|override|final|mutable|constexpr|&&|&))*"
INIT = r"[\w:]+(?:\s*<[^(){};]*>)?\s*(?:\(\)|\{\})"
TAIL = re.compile(QUALIFIERS + r"(?:\s*->\s*[^{};=]+?)?" + QUALIFIERS +
                  r"(?:\s*:\s*" + INIT + r"(?:\s*,\s*" + INIT + r")*(?:\s*\.\.\.)?)?\s*$")
NAME = re.compile(r"((?:[\w:~]*\s*::\s*)?operator\s*(?:\(\)|\[\]|new\b|delete\b|[^\s\w(]+|\s[\w:<>*&\s]+?)"
                  r"|~?[A-Za-z_][\w]*(?:\s*::\s*~?[A-Za-z_]\w*)*(?:\s*<[^()]*>)?)\s*$")
LAMBDA = re.compile(r"\[[^\[\]]*\]\s*(?:\(\))?" + QUALIFIERS + r"(?:\s*->\s*[^{};=]+?)?\s*$")
KEYWORDS = {"if", "for", "while", "switch", "catch", "return", "sizeof", "decltype", "alignas"}


def classify(head):
    """What a `{` opened after `head` (code since the last `;` or scope brace) at namespace or
    class scope is: ('scope', None), ('function', name) or ('other', None)."""
    h = re.sub(r"\[\[.*?\]\]", " ", head).strip()
    h = re.sub(r"^(?:(?:public|private|protected)\s*:(?!:)\s*)+", "", h)
    if h.count("(") != h.count(")"):
        return "other", None  # a brace inside an argument list (a default argument)
    if re.match(r"(?:inline\s+)?namespace\b", h) or re.fullmatch(r'extern\s*"[^"]*"', h):
        return "scope", None
    h = strip_template_prefix(h)
    c = collapse(h)
    if re.match(r"(?:typedef\s+)?enum\b", c):
        return "other", None
    if re.match(r"(?:typedef\s+|friend\s+)?(?:class|struct|union)\b", c) and "=" not in c:
        return "scope", None
    lam = LAMBDA.search(c)
    if lam and "=" in c[:lam.start()]:
        var = re.search(r"(\w+)\s*=\s*$", c[:lam.start()])
        return "function", "lambda " + (var.group(1) if var else "?")
    for m in re.finditer(r"\(\)", c):
        if not TAIL.match(c, m.end()):
            continue
        name = NAME.search(c[:m.start()])
        if not name:
            return "other", None
        text = re.sub(r"\s+", "", name.group(1)) if "operator" not in name.group(1) \
            else re.sub(r"\s+", " ", name.group(1)).strip()
        if text in KEYWORDS:
            return "other", None
        return "function", text
    return "other", None


def match_brace(code, i):
    """Offset just past the `}` that closes the `{` at i."""
    depth = 0
    n = len(code)
    while i < n:
        if code[i] == "{":
            depth += 1
        elif code[i] == "}":
            depth -= 1
            if depth == 0:
                return i + 1
        i += 1
    return n


def find_functions(text):
    """[(name, first line of signature, opening-brace line, closing-brace line)] of text."""
    code, _ = blank_non_code(text)
    line_of = []
    ln = 1
    for ch in code:
        line_of.append(ln)
        if ch == "\n":
            ln += 1
    line_of.append(ln)
    found = []

    def scan(i, end):
        head_start = None
        while i < end:
            c = code[i]
            if c == "}":
                return i + 1
            if c == ";":
                head_start = None
                i += 1
                continue
            if c == "{":
                head = code[head_start:i] if head_start is not None else ""
                kind, name = classify(head)
                close = match_brace(code, i)
                if kind == "scope":
                    scan(i + 1, close)
                    head_start = None
                elif kind == "function":
                    start = head_start if head_start is not None else i
                    found.append((name, line_of[start], line_of[i], line_of[close - 1]))
                    head_start = None
                elif head_start is None:
                    head_start = i
                i = close
                continue
            if head_start is None and not c.isspace():
                head_start = i
            i += 1
        return i

    scan(0, len(code))
    return found


def has_reason(text_lines, comments, sig_line, brace_line):
    """A `long-function:` comment on the signature's lines or in the comment block above it."""
    for ln in range(sig_line, brace_line + 1):
        if MARKER.search(comments.get(ln, "")):
            return True
    ln = sig_line - 1
    while ln >= 1:
        code_part = text_lines[ln - 1]
        cm = comments.get(ln)
        if cm is None:
            return False  # a blank or code line ends the block
        if MARKER.search(cm):
            return True
        stripped = code_part.strip()
        if not (stripped.startswith("//") or stripped.startswith("/*") or stripped.startswith("*")):
            return False  # a comment that trails code belongs to that code
        ln -= 1
    return False


def check_text(text):
    """[(name, signature line, length, accepted)] for every function over LIMIT lines."""
    _, comments = blank_non_code(text)
    lines = text.split("\n")
    long = []
    for name, sig, open_ln, close_ln in find_functions(text):
        length = close_ln - open_ln + 1
        if length > LIMIT:
            long.append((name, sig, length, has_reason(lines, comments, sig, open_ln)))
    return long


def main(root):
    files = sorted(glob.glob(os.path.join(root, "src", "**", "*.cpp"), recursive=True) +
                   glob.glob(os.path.join(root, "src", "**", "*.hpp"), recursive=True))
    scanned = 0
    offenders = []
    marked = 0
    for path in files:
        text = open(path, encoding="utf-8").read()
        scanned += len(find_functions(text))
        for name, sig, length, accepted in check_text(text):
            if accepted:
                marked += 1
            else:
                offenders.append("%s:%d: %s: %d lines" % (os.path.relpath(path, root), sig, name, length))
    for o in offenders:
        print(o)
    if offenders:
        print("  split these, or write `// long-function: REASON` just above the signature")
    print("check_function_length: %d functions in %d files, %d over %d lines without a reason, "
          "%d with one" % (scanned, len(files), len(offenders), LIMIT, marked))
    return 1 if offenders else 0


def body(lines):
    return "\n".join("  x += %d;" % k for k in range(lines))


def self_test():
    """The scanner on small snippets: each case (name, C++ text, expected check_text result)."""
    f80 = "int f80(int x) {\n" + body(77) + "\n  return x;\n}\n"      # 80 lines with the braces
    f81 = "int f81(int x) {\n" + body(78) + "\n  return x;\n}\n"      # 81 lines
    cases = [
        ("81 lines flagged", f81, [("f81", 1, 81, False)]),
        ("80 lines not flagged", f80, []),
        ("marked one accepted",
         "// Does things.\n// long-function: one table of the 81 kinds\n" + f81,
         [("f81", 3, 81, True)]),
        ("marker without a reason is no reason", "// long-function:\n" + f81,
         [("f81", 2, 81, False)]),
        ("marker of an earlier function is not inherited",
         "// long-function: a table\nint a();\n\n" + f81, [("f81", 4, 81, False)]),
        ("braces in strings, chars and comments ignored",
         "const char* s = \"{{{\";\nchar c = '{';\nauto r = R\"x({ \")x\";\n// {\n/* } { */\n" + f81 +
         "int g() {\n  return '}' + \"}}\"[0]; // }\n}\n",
         [("f81", 6, 81, False)]),
        ("class body is not a function; its long member is",
         "namespace a {\ntemplate <class T>\nclass Big : public Base<T> {\n public:\n" +
         body(90).replace("x +=", "int m") + "\n" + f81.replace("int f81", "  int f81") +
         "};\n}  // namespace a\n",
         [("f81", 95, 81, False)]),
        ("long struct and enum bodies are not functions",
         "struct S {\n" + body(90).replace("x +=", "int m") + "\n};\nenum class E {\n" +
         ",\n".join("  e%d" % k for k in range(90)) + "\n};\n", []),
        ("lambdas inside count with their function; constructor with brace initialisers",
         "A::A(int n) : a_{n}, b_(n) {\n  auto l = [&](int k) {\n" + body(40) + "\n  };\n" +
         body(40) + "\n}\n", [("A::A", 1, 84, False)]),
        ("digit separators and default brace arguments",
         "void h(std::vector<int> v = {}) const {\n  int big = 1'000'000;\n" + body(80) + "\n}\n",
         [("h", 1, 83, False)]),
        ("preprocessor lines and operators",
         "#define OPEN {\nbool operator==(const A& a, const A& b) {\n#pragma omp parallel for\n" +
         body(80) + "\n}\n", [("operator==", 2, 83, False)]),
    ]
    failed = 0
    for name, text, want in cases:
        got = check_text(text)
        if got != want:
            failed += 1
            print("FAIL %s: got %s, want %s" % (name, got, want))
            print("  functions: %s" % find_functions(text))
        else:
            print("ok   %s" % name)
    print("check_function_length --self-test: %d of %d cases passed" % (len(cases) - failed, len(cases)))
    return 1 if failed else 0


if __name__ == "__main__":
    args = [a for a in sys.argv[1:] if a != "--self-test"]
    if "--self-test" in sys.argv[1:]:
        sys.exit(self_test())
    sys.exit(main(os.path.abspath(args[0] if args else ".")))
