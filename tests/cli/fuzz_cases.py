#!/usr/bin/python3
"""Fuzzed case files: mutate the shipped case files N times (fixed seed) and run
`cgdem run MUTANT --check` on each (validate, build the scene, insert the parcels; no step).

Required of every mutant:
  * no signal, no abort or uncaught exception, no hang (a timeout counts as a failure);
  * exit 0 (accepted) or non-zero with "cgdem: error:" and a message that names
      - for a value changed in the file: the file with a line number ("FILE:LINE:"),
      - for a syntax error (truncated file, garbage, duplicate key or table): "FILE:LINE:",
      - for an unknown key: "unknown key 'PATH'", at its line, with "did you mean 'KEY'"
        when the key is a misspelling of a known key of the same table,
      - for a value given with --set: "command line (--set '...')", and not the file;
  * never accepted: NaN, inf, a string where a number is expected, binary garbage,
    duplicate keys and tables, unknown keys.
Accepted mutants are listed with the reason they may be right (a value inside the
documented range, a key with a default); the counts are printed.

  fuzz_cases.py --cgdem BUILD/cgdem --root SOURCE --work DIR [--count 200] [--seed 21]
"""
import os
import random
import re
import subprocess
import sys
import time

import cli_script  # tests/cli/cli_script.py: the options and the verdict

SEEDS = [
    "tests/cli/base.toml", "tests/cli/moving_wall.toml", "tests/cli/escape.toml", "tests/cli/mpi_bed_air.toml",
    "cases/die_filling_vacuum_l3.toml", "validation/die_filling/case_1_3.toml", "validation/die_filling/case_2_4.toml",
    "validation/die_filling/case_2_2.toml", "validation/die_filling_slab/slab_1_3.toml",
    "validation/scaling_column_collapse/case.toml", "validation/taylor_green/taylor_green.toml",
    "tests/cli/converge/taylor_green_dt.toml",
]

KEY_LINE = re.compile(r'^(\s*)([A-Za-z0-9_]+)(\s*=\s*)(.*?)(\s*(#.*)?)$')
TABLE = re.compile(r'^\s*\[([A-Za-z0-9_.]+)\]\s*(#.*)?$')
ARRAY_TABLE = re.compile(r'^\s*\[\[([A-Za-z0-9_.]+)\]\]\s*(#.*)?$')


def scan(lines):
    """(line index, key path, value text) of every one-line `key = value`, with the table headers."""
    keys, tables, prefix, counts = [], [], "", {}
    for i, line in enumerate(lines):
        m = ARRAY_TABLE.match(line)
        if m:
            name = m.group(1)
            counts[name] = counts.get(name, -1) + 1
            for k in [k for k in counts if k.startswith(name + ".")]:
                del counts[k]  # a new element: its nested arrays start again
            # nested arrays ([[walls.body.part]]) belong to the last element of the parent
            parts = name.split(".")
            path = ""
            for k in range(len(parts)):
                head = ".".join(parts[:k + 1])
                path = (path + "." if path else "") + parts[k]
                if head in counts and head != name:
                    path += "[%d]" % counts[head]
            prefix = path + "[%d]" % counts[name]
            continue
        m = TABLE.match(line)
        if m:
            prefix = m.group(1)
            tables.append((i, prefix))
            continue
        m = KEY_LINE.match(line)
        if m and m.group(4) and not m.group(4).startswith('"""') and \
                (not m.group(4).startswith("[") or m.group(4).endswith("]")):
            keys.append((i, (prefix + "." if prefix else "") + m.group(2), m.group(4)))
    return keys, tables


def typo(rng, name):
    """A misspelling at edit distance 1 (dropped, doubled or swapped letter)."""
    i = rng.randrange(len(name))
    kind = rng.choice(["drop", "double", "swap"]) if len(name) > 3 else "double"
    if kind == "drop":
        return name[:i] + name[i + 1:]
    if kind == "double":
        return name[:i] + name[i] + name[i:]
    i = min(i, len(name) - 2)
    swapped = name[:i] + name[i + 1] + name[i] + name[i + 2:]
    return swapped if swapped != name else name + name[-1]


VALUE_MUTATIONS = ["nan", "inf", "-inf", "negative", "1e308", "1e-30", "zero", "huge_integer", "string", "boolean",
                   "array", "table"]


def mutate(rng, text):
    """Returns (kind, mutated text, info dict)."""
    lines = text.split("\n")
    keys, tables = scan(lines)
    kind = rng.choice(["delete_key"] * 2 + ["value"] * 8 + ["truncate", "garbage", "garbage_line", "duplicate_key",
                       "duplicate_table", "unknown_key", "typo_key", "set_value", "set_value"])
    if kind == "duplicate_table" and not tables:
        kind = "duplicate_key"
    info = {}
    if kind in ("delete_key", "value", "duplicate_key", "typo_key", "set_value"):
        i, path, value = rng.choice(keys)
        info.update(line=i + 1, path=path, old=value)
        m = KEY_LINE.match(lines[i])
        if kind == "delete_key":
            del lines[i]
        elif kind == "duplicate_key":
            lines.insert(i + 1, lines[i])
            info["line"] = i + 2
        elif kind == "typo_key":
            new = typo(rng, m.group(2))
            lines[i] = m.group(1) + new + m.group(3) + m.group(4)
            info["new_path"] = path[:len(path) - len(m.group(2))] + new
        else:
            v = rng.choice(VALUE_MUTATIONS)
            num = re.fullmatch(r'[-+]?[0-9][0-9_]*(\.[0-9_]*)?([eE][-+]?[0-9]+)?', value) is not None
            new = {"nan": "nan", "inf": "inf", "-inf": "-inf", "1e308": "1e308", "1e-30": "1e-30", "zero": "0",
                   "huge_integer": "9999999999999999999", "string": '"text"', "boolean": "true", "array": "[1, 2]",
                   "table": "{ a = 1 }"}.get(v)
            if v == "negative":
                new = ("-" + value) if num and not value.startswith("-") else ("-1" if not num else value[1:])
            info.update(value_kind=v, new=new)
            if kind == "value":
                lines[i] = m.group(1) + m.group(2) + m.group(3) + new + m.group(5)
            else:
                info["set"] = "%s=%s" % (path, new)
        kind = kind if kind != "value" else "value:" + info["value_kind"]
        if kind == "set_value":
            kind = "set_value:" + info["value_kind"]
        return kind, "\n".join(lines), info
    if kind == "truncate":
        cut = rng.randrange(1, len(text))
        return kind, text[:cut], {"cut": cut}
    if kind == "garbage":
        n = rng.randrange(1, 64)
        at = rng.randrange(len(text))
        junk = bytes(rng.randrange(256) for _ in range(n)).decode("latin-1")
        line = text[text.rfind("\n", 0, at) + 1:at]
        in_comment = "#" in line and '"' not in line and "\n" not in junk and "\r" not in junk
        return kind, text[:at] + junk + text[at:], {"at": at, "bytes": n, "in_comment": in_comment}
    if kind == "garbage_line":
        i = rng.randrange(len(lines))
        lines.insert(i, "".join(chr(rng.randrange(33, 127)) for _ in range(rng.randrange(3, 20))))
        return kind, "\n".join(lines), {"line": i + 1}
    if kind == "duplicate_table":
        i, name = rng.choice(tables)
        lines.append("[%s]" % name)
        return kind, "\n".join(lines), {"line": len(lines), "path": name}
    # unknown_key: a new key in a table of the file
    if tables and rng.random() < 0.7:
        i, name = rng.choice(tables)
        lines.insert(i + 1, "zz_not_a_key = 1")
        return kind, "\n".join(lines), {"line": i + 2, "new_path": name + ".zz_not_a_key"}
    lines.insert(0, "zz_not_a_key = 1")
    return kind, "\n".join(lines), {"line": 1, "new_path": "zz_not_a_key"}


def judge_accepted(kind, info):
    """Why accepting may be right, or None if it never is."""
    base = kind.split(":")[0]
    v = kind.split(":")[1] if ":" in kind else ""
    if base == "garbage" and info.get("in_comment"):
        return "the bytes landed inside a comment (no line break among them), which is ignored"
    if base in ("garbage", "garbage_line", "duplicate_key", "duplicate_table", "unknown_key", "typo_key"):
        return None
    if v in ("nan", "inf", "-inf", "string", "huge_integer", "array", "table"):
        return None
    if base == "delete_key":
        return "the key has a default (see config.resolved.toml)"
    if base == "truncate":
        return "the cut left a complete file (in a comment or after the last required key)"
    return "the new value lies inside the key's documented range"


def main():
    args = cli_script.parse_args("root", "work", count=200, seed=21)
    rng = random.Random(args.seed)
    os.makedirs(args.work, exist_ok=True)
    texts = {s: open(os.path.join(args.root, s), encoding="latin-1").read() for s in SEEDS}
    stats = {"tried": 0, "rejected_ok": 0, "accepted": 0, "crashes": 0, "bad_message": 0, "wrongly_accepted": 0,
             "named_mutated_key": 0, "named_mutated_line": 0, "did_you_mean": 0, "set_attributed": 0}
    accepted, failures, through_other = [], [], []
    t0 = time.time()
    for n in range(args.count):
        seed_file = SEEDS[n % len(SEEDS)]
        kind, text, info = mutate(rng, texts[seed_file])
        # The mutant sits beside the work folder under the seed's base name, so that the
        # message must name it (relative paths inside the case: none in these seeds).
        name = "%03d_%s" % (n, os.path.basename(seed_file))
        path = os.path.join(args.work, name)
        cmd = [args.cgdem, "run", path, "--check"]
        if kind.startswith("set_value"):
            text = texts[seed_file]
            cmd += ["--set", info["set"]]
        with open(path, "w", encoding="latin-1") as f:
            f.write(text)
        stats["tried"] += 1
        label = "%s %s %s" % (name, kind, info)
        try:
            p = subprocess.run(cmd, capture_output=True, timeout=30, env=dict(os.environ, OMP_NUM_THREADS="1"))
        except subprocess.TimeoutExpired:
            stats["crashes"] += 1
            failures.append("HANG (> 30 s): " + label)
            continue
        err = p.stderr.decode("utf-8", "replace")
        if p.returncode < 0 or p.returncode > 3 or re.search(r"terminate called|Segmentation|Aborted|core dumped", err):
            stats["crashes"] += 1
            failures.append("CRASH rc=%d: %s\n      %s" % (p.returncode, label, err.strip()[:400]))
            continue
        if p.returncode == 0:
            stats["accepted"] += 1
            why = judge_accepted(kind, info)
            if why is None:
                stats["wrongly_accepted"] += 1
                failures.append("ACCEPTED but must not be: " + label)
            accepted.append("%s\n      -> accepted: %s" % (label, why or "WRONG"))
            continue
        # rejected: check the message
        msg = err.strip()
        problems = []
        if "cgdem: error:" not in msg:
            problems.append("no 'cgdem: error:'")
        if kind.startswith("set_value"):
            if "command line (--set '%s')" % info["set"] not in msg:
                problems.append("not attributed to the command line")
            elif path + ":" in msg:
                problems.append("names the file for a --set value")
            else:
                stats["set_attributed"] += 1
        elif re.search(re.escape(path) + r": key '[a-z_]+': missing", msg):
            pass  # a missing top-level table: no line to name, the file and the key are named
        elif not re.search(re.escape(path) + r":[0-9]+: ", msg):
            problems.append("no FILE:LINE")
        if kind.startswith("value") or kind.startswith("set_value"):
            if "key '%s'" % info["path"] in msg:
                stats["named_mutated_key"] += 1
                if kind.startswith("value") and "%s:%d: key '%s'" % (path, info["line"], info["path"]) in msg:
                    stats["named_mutated_line"] += 1
            else:
                through_other.append("%s %s=%s -> %s" % (name, info["path"], info["new"],
                                                         msg.replace(path, "FILE").splitlines()[0][14:200]))
        if kind in ("unknown_key", "typo_key"):
            if "unknown key '%s'" % info["new_path"] not in msg and "missing" not in msg:
                problems.append("does not name the unknown key " + info["new_path"])
            if kind == "typo_key" and "unknown key" in msg:
                if "did you mean '%s'" % info["path"] in msg:
                    stats["did_you_mean"] += 1
                else:
                    problems.append("no \"did you mean '%s'\"" % info["path"])
        if kind in ("duplicate_key", "duplicate_table", "truncate", "garbage", "garbage_line") and \
                "unknown key" not in msg and "key '" not in msg and "syntax error" not in msg:
            problems.append("neither a key nor a syntax error named")
        if problems:
            stats["bad_message"] += 1
            failures.append("BAD MESSAGE (%s): %s\n      %s" % ("; ".join(problems), label, msg[:600]))
        else:
            stats["rejected_ok"] += 1
    wall = time.time() - t0
    print("fuzzed case files: seed %d, %d mutants of %d shipped files in %.1f s" % (args.seed, stats["tried"],
                                                                                   len(SEEDS), wall))
    print("  rejected with a message naming the file and line (or the --set option) and the key: %d"
          % stats["rejected_ok"])
    print("    of which naming the mutated key: %d (at its line: %d); did you mean: %d; --set attributed to the "
          "command line: %d" % (stats["named_mutated_key"], stats["named_mutated_line"], stats["did_you_mean"],
                                stats["set_attributed"]))
    print("  value mutations rejected through another key (a check that depends on the value): %d"
          % len(through_other))
    for t in through_other:
        print("    " + t)
    print("  accepted: %d (must-never-accept among them: %d)" % (stats["accepted"], stats["wrongly_accepted"]))
    for a in accepted:
        print("    " + a)
    print("  rejected with a bad message: %d" % stats["bad_message"])
    print("  crashes (signal, abort, uncaught exception, hang): %d" % stats["crashes"])
    for f in failures:
        print("  FAIL " + f)
    ok = stats["crashes"] == 0 and stats["bad_message"] == 0 and stats["wrongly_accepted"] == 0
    print("PASS" if ok else "FAILED: crashes, bad messages and wrong acceptances must all be 0")
    return 0 if ok else 1


if __name__ == "__main__":
    sys.exit(main())
