"""The mutants of scripts/mutate.sh: every match of an operator (operators.py) on a source line, keyed stably,
and the deterministic sample of them. See docs/testing.md."""

import hashlib
import re

from operators import OPERATORS

SKIP_LINE = re.compile(r"^\s*(#|//)|\bthrow\b|\bError\(|fprintf|std::cout|std::cerr|static_assert|\btrace\b")


def blank_literals_and_comments(line):
    """The line with string/char literal contents and a trailing // comment replaced by spaces (same length),
    so operators never match inside them."""
    out, i, quote = [], 0, None
    while i < len(line):
        c = line[i]
        if quote:
            if c == "\\":
                out.append("  ")
                i += 2
                continue
            out.append(c if c == quote else " ")
            if c == quote:
                quote = None
        elif c in "\"'":
            quote = c
            out.append(c)
        elif line.startswith("//", i):
            out.append(" " * (len(line) - i))
            break
        else:
            out.append(c)
        i += 1
    return "".join(out)[: len(line)]


def mutants_of(rel_path, text):
    """Every mutant of one source file: dicts with a stable key (file, operator, line text, occurrence)."""
    lines = text.split("\n")
    result, in_block_comment = [], False
    seen = {}  # stripped line text -> how many times it has occurred so far
    for number, line in enumerate(lines, start=1):
        stripped = line.strip()
        if in_block_comment:
            in_block_comment = "*/" not in stripped
            continue
        if stripped.startswith("/*"):
            in_block_comment = "*/" not in stripped
            continue
        if SKIP_LINE.search(line):
            continue
        masked = blank_literals_and_comments(line)
        repeat = seen.get(stripped, 0)
        seen[stripped] = repeat + 1
        for name, pattern, replacement in OPERATORS:
            for occurrence, match in enumerate(re.finditer(pattern, masked)):
                new_text = match.expand(replacement) if isinstance(replacement, str) else replacement(match)
                mutated = line[: match.start()] + new_text + line[match.end() :]
                if mutated == line:
                    continue
                # The key names the line by its text (stable when other lines move); an identical line
                # seen before in the file gets its repeat count, so each copy is a mutant of its own.
                ident = f"{rel_path}|{name}|{line.strip()}|{occurrence}"
                ident += f"|{repeat}" if repeat else ""
                digest = hashlib.sha1(ident.encode()).hexdigest()
                result.append({"key": digest[:12], "file": rel_path, "line": number, "operator": name,
                               "original": line.strip(), "mutated": mutated.strip(), "text": mutated})
    return result


def sampled(mutant, fraction, seed):
    """Deterministic sample: a mutant is in if the hash of (seed, key) falls below the fraction."""
    if fraction >= 1:
        return True
    h = int(hashlib.sha1(f"{seed}|{mutant['key']}".encode()).hexdigest()[:8], 16)
    return h < fraction * 0x100000000
