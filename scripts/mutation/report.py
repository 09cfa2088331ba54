"""The Markdown report of scripts/mutate.sh: the score per module and one line per mutant, with the survivors
shown to be equivalent (equivalent.txt) not counted. See docs/testing.md."""

from pathlib import Path


def module_of(rel_path):
    parts = Path(rel_path).parts
    return "/".join(parts[:2]) if len(parts) > 2 else parts[0]


def load_equivalents():
    """scripts/mutation/equivalent.txt: `KEY  reason` lines for survivors shown to be equivalent."""
    path = Path(__file__).resolve().parent / "equivalent.txt"
    result = {}
    if path.exists():
        for line in path.read_text().splitlines():
            if line.strip() and not line.startswith("#"):
                key, _, reason = line.strip().partition(" ")
                result[key] = reason.strip()
    return result


def write_report(results, path, command):
    equivalents = load_equivalents()
    modules = {}
    for r in results:
        m = modules.setdefault(module_of(r["file"]), {"mutants": 0, "killed": 0, "equivalent": 0,
                                                      "survived": 0, "stillborn": 0})
        if r["outcome"] == "stillborn":
            m["stillborn"] += 1
            continue
        if r["outcome"] == "same-object" or (r["outcome"] == "survived" and r["key"] in equivalents):
            m["equivalent"] += 1
            continue
        m["mutants"] += 1
        m["killed" if r["outcome"] in ("killed", "timeout") else "survived"] += 1
    lines = [f"Produced by `{command}`.", "",
             "| module | mutants | killed | survived | score | equivalent (not counted) | stillborn |",
             "|---|---|---|---|---|---|---|"]
    total = {"mutants": 0, "killed": 0}
    for name, m in sorted(modules.items()):
        score = 100.0 * m["killed"] / m["mutants"] if m["mutants"] else 100.0
        total["mutants"] += m["mutants"]
        total["killed"] += m["killed"]
        lines.append(f"| {name} | {m['mutants']} | {m['killed']} | {m['survived']} | {score:.1f} % | "
                     f"{m['equivalent']} | {m['stillborn']} |")
    if total["mutants"]:
        lines.append(f"| **all** | {total['mutants']} | {total['killed']} | "
                     f"{total['mutants'] - total['killed']} | {100.0 * total['killed'] / total['mutants']:.1f} % "
                     "| | |")
    lines += ["", "| mutant | where | operator | change | outcome |", "|---|---|---|---|---|"]
    for r in sorted(results, key=lambda r: (r["file"], r["line"], r["operator"])):
        if r["outcome"] == "stillborn":
            continue
        outcome = {"killed": f"killed by {r.get('killer')}", "timeout": f"killed (timeout in {r.get('killer')})",
                   "same-object": "equivalent: same object code"}.get(r["outcome"], "")
        if r["outcome"] == "survived":
            outcome = f"equivalent: {equivalents[r['key']]}" if r["key"] in equivalents else "**survived**"
            if "results_same" in r:
                outcome += " (pinned batch: " + ("same results" if r["results_same"] else "results change") + ")"
        change = f"`{r['original']}` → `{r['mutated']}`".replace("|", "\\|")
        lines.append(f"| {r['key']} | {r['file']}:{r['line']} | {r['operator']} | {change} | {outcome} |")
    Path(path).write_text("\n".join(lines) + "\n")
    return lines
