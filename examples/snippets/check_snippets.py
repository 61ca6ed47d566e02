#!/usr/bin/env python3
"""Checks that every ```cpp block of the documents appears verbatim in a compiled example.

    python3 examples/snippets/check_snippets.py [REPO_ROOT]

Each ```cpp block of README.md and docs/library.md must equal, line for line, exactly one region
of examples/snippets/*.cpp marked

    // snippet begin: README.md
    ...the block...
    // snippet end

(the region's lines may be indented by the begin marker's indentation), and every marked region
must be some block of the document it names. The examples are built and run against the installed
package by cmake/test_snippets.cmake (ctest -R footprint-doc-snippets). A block that is not meant
to compile (a list of declarations) is opted out by the line `<!-- snippet: not compiled -->`
right before its fence. Exits with 1, naming each document, block and first line that do not
match.
"""
import pathlib
import re
import sys

DOCUMENTS = ["README.md", "docs/library.md"]
OPT_OUT = "<!-- snippet: not compiled -->"
BEGIN = re.compile(r"^(\s*)// snippet begin: (\S+)\s*$")
END = re.compile(r"^\s*// snippet end\s*$")


def doc_blocks(path):
    """The document's ```cpp blocks: (number, first line number, lines, opted out)."""
    lines = path.read_text(encoding="utf-8").splitlines()
    blocks, i, number = [], 0, 0
    while i < len(lines):
        if lines[i].strip() == "```cpp":
            number += 1
            opted_out = i > 0 and lines[i - 1].strip() == OPT_OUT
            start = i + 1
            j = start
            while j < len(lines) and lines[j].strip() != "```":
                j += 1
            blocks.append((number, start + 1, lines[start:j], opted_out))
            i = j + 1
        else:
            i += 1
    return blocks


def example_regions(folder, errors):
    """The marked regions of folder/*.cpp: (document, file, line number, lines)."""
    regions = []
    for file in sorted(folder.glob("*.cpp")):
        lines = file.read_text(encoding="utf-8").splitlines()
        i = 0
        while i < len(lines):
            begin = BEGIN.match(lines[i])
            if not begin:
                i += 1
                continue
            indent, document = begin.group(1), begin.group(2)
            j = i + 1
            body = []
            while j < len(lines) and not END.match(lines[j]):
                line = lines[j]
                if line.strip() and not line.startswith(indent):
                    errors.append(f"{file.name}:{j + 1}: a line of the region is indented less "
                                  "than its '// snippet begin' marker")
                body.append(line[len(indent):] if line.strip() else "")
                j += 1
            if j == len(lines):
                errors.append(f"{file.name}:{i + 1}: '// snippet begin' without '// snippet end'")
            regions.append((document, file.name, i + 1, body))
            i = j + 1
    return regions


def main():
    root = pathlib.Path(sys.argv[1] if len(sys.argv) > 1 else pathlib.Path(__file__).parents[2])
    errors = []
    regions = example_regions(root / "examples" / "snippets", errors)
    used = set()
    checked = 0
    for document in DOCUMENTS:
        for number, line, block, opted_out in doc_blocks(root / document):
            if opted_out:
                continue
            checked += 1
            first = next((l.strip() for l in block if l.strip()), "(empty)")
            matches = [k for k, (doc, _, _, body) in enumerate(regions)
                       if doc == document and [l.rstrip() for l in body] ==
                       [l.rstrip() for l in block]]
            if not matches:
                errors.append(f"{document}, C++ block {number} (line {line}, '{first}'): not "
                              "in any '// snippet begin: " + document + "' region of "
                              "examples/snippets/*.cpp; copy it there, where it compiles and "
                              f"runs, or mark it '{OPT_OUT}' if it is a list of declarations")
            elif len(matches) > 1:
                where = ", ".join(f"{regions[k][1]}:{regions[k][2]}" for k in matches)
                errors.append(f"{document}, C++ block {number} (line {line}, '{first}'): in "
                              f"several regions ({where}); keep one")
            used.update(matches)
    for k, (document, file, line, body) in enumerate(regions):
        if k in used:
            continue
        first = next((l.strip() for l in body if l.strip()), "(empty)")
        if document not in DOCUMENTS:
            errors.append(f"{file}:{line}: the region names '{document}', which is not one of "
                          f"{', '.join(DOCUMENTS)}")
        else:
            errors.append(f"{file}:{line}: the region ('{first}') is no C++ block of "
                          f"{document}: the document's block was changed or removed; change "
                          "the example to match it, or remove the region")
    for error in errors:
        print(error, file=sys.stderr)
    if errors:
        print(f"{len(errors)} mismatch(es) between the documents' C++ blocks and "
              "examples/snippets/", file=sys.stderr)
        return 1
    print(f"{checked} C++ blocks of {', '.join(DOCUMENTS)} match examples/snippets/")
    return 0


if __name__ == "__main__":
    sys.exit(main())
