"""The layout of src/ (src/README.md) holds:

- every file's name is unique across src/'s folders (the files include each other by name,
  and an FMU's sources/ holds them in one folder: fmu/tools/make_sources.py);
- every quoted include names a file of src/, and one a folder's README allows (MAY_INCLUDE);
- no cycle between source files: none among the includes, of files or of a C file with its
  header (model.c and model.h are one unit), and none between the core's object files by
  the functions and data one uses of another (nm), so that each part reads, and can be
  tested, from the bottom up.

    python check_sources.py <src folder> [<the core's static library>]

Each failure is printed as one line; the exit status is 1 if there is any.
"""

import collections
import os
import re
import subprocess
import sys

# What the files of each folder may include besides their own folder's (each folder's
# README.md says why): other folders, or single files of them.
MAY_INCLUDE = {
    "common": {"tribo.h"},
    "chute": {"common", "chute/charge", "chute/integrators"},
    "chute/charge": {"common", "tribo.h", "geometry.h"},
    "chute/integrators": {"common", "chute/charge", "tribo.h", "contact.h", "dynamics.h",
                          "force_phases.h", "flight.h", "motion.h"},
    "si": {"common", "tribo.h", "quantities.def", "charge_registry.h", "charge_registry.def",
           "geometry.h", "paschen.h"},
    "separator": {"common", "tribo.h"},
}
SOURCE = (".c", ".h", ".def")
INCLUDE = re.compile(r'^\s*#\s*include\s+"([^"]+)"', re.MULTILINE)


def source_files(src):
    """{file name: folder relative to src} of every source file, and the problems of names
    that are not unique."""
    where, problems = {}, []
    for folder, _, names in sorted(os.walk(src)):
        relative = os.path.relpath(folder, src).replace(os.sep, "/")
        for name in sorted(n for n in names if n.endswith(SOURCE)):
            if name in where:
                problems.append(f"{name} is in both {where[name]}/ and {relative}/: a file's "
                                f"name must be unique across src/")
            where.setdefault(name, relative)
    return where, problems


def includes(src, where):
    """{file: [included file, ...]} of every quoted include, and the problems of includes
    that name no file of src/ or one the including folder may not include."""
    graph, problems = {}, []
    for name, folder in sorted(where.items()):
        with open(os.path.join(src, folder, name), encoding="utf-8") as f:
            text = f.read()
        graph[name] = []
        for included in INCLUDE.findall(text):
            if included not in where:
                problems.append(f"{folder}/{name} includes \"{included}\", which is no file of src/")
                continue
            graph[name].append(included)
            other = where[included]
            allowed = MAY_INCLUDE.get(folder)
            if allowed is None:
                problems.append(f"{folder}/ is a folder check_sources.py does not know: "
                                f"add it to MAY_INCLUDE, as its README says")
            elif other != folder and other not in allowed and included not in allowed:
                problems.append(f"{folder}/{name} includes {other}/{included}, which {folder}/ "
                                f"may not include ({folder}/README.md)")
    return graph, problems


def cycles(graph):
    """The strongly connected components of more than one node, or of one with an edge to
    itself (Tarjan's algorithm, iterative)."""
    index, low, on_stack, stack, found = {}, {}, set(), [], []
    counter = 0
    for root in sorted(graph):
        if root in index:
            continue
        work = [(root, iter(sorted(graph.get(root, ()))))]
        index[root] = low[root] = counter
        counter += 1
        stack.append(root)
        on_stack.add(root)
        while work:
            node, edges = work[-1]
            for nxt in edges:
                if nxt not in index:
                    index[nxt] = low[nxt] = counter
                    counter += 1
                    stack.append(nxt)
                    on_stack.add(nxt)
                    work.append((nxt, iter(sorted(graph.get(nxt, ())))))
                    break
                if nxt in on_stack:
                    low[node] = min(low[node], index[nxt])
            else:
                work.pop()
                if work:
                    low[work[-1][0]] = min(low[work[-1][0]], low[node])
                if low[node] == index[node]:
                    component = []
                    while True:
                        member = stack.pop()
                        on_stack.discard(member)
                        component.append(member)
                        if member == node:
                            break
                    if len(component) > 1 or node in graph.get(node, ()):
                        found.append(sorted(component))
    return found


def describe(component, edges):
    """The edges within a cycle, for the message: 'a -> b (why)'."""
    inside = set(component)
    return "; ".join(f"{a} -> {b}{f' ({why})' if why else ''}"
                     for a in component for b, why in sorted(edges.get(a, {}).items()) if b in inside)


def include_cycles(graph):
    problems = []
    files = {a: {b: "" for b in bs} for a, bs in graph.items()}
    for component in cycles({a: set(bs) for a, bs in files.items()}):
        problems.append(f"an include cycle: {describe(component, files)}")
    # a C file and its header are one unit (model.c with model.h)
    def unit(name):
        return os.path.splitext(name)[0] if name.endswith((".c", ".h")) else name
    units = collections.defaultdict(dict)
    for a, bs in graph.items():
        for b in bs:
            if unit(a) != unit(b):
                units[unit(a)].setdefault(unit(b), f"{a} includes {b}")
    for component in cycles({a: set(bs) for a, bs in units.items()}):
        problems.append(f"a cycle of includes between C files and their headers: "
                        f"{describe(component, units)}")
    return problems


def symbol_cycles(library):
    """The cycles between the library's object files, each an edge where one uses a function
    or data that another defines."""
    def nm(*options):
        out = subprocess.run(["nm", "-A", *options, library], capture_output=True, text=True)
        if out.returncode != 0:
            sys.exit(f"check_sources: nm {library}: {out.stderr.strip()}")
        for line in out.stdout.splitlines():
            fields = line.split()
            # "<library>:<object>: [address] <type> <symbol>"
            yield fields[0].split(":")[-2], fields[-2], fields[-1]
    defined = {symbol: obj for obj, kind, symbol in nm("--defined-only") if kind.isupper()}
    uses = collections.defaultdict(dict)
    for obj, _, symbol in nm("--undefined-only"):
        owner = defined.get(symbol)
        if owner and owner != obj:
            uses[obj].setdefault(owner, symbol)
    strip = lambda o: re.sub(r"\.(c\.)?o(bj)?$", ".c", o)
    edges = {strip(a): {strip(b): why for b, why in bs.items()} for a, bs in uses.items()}
    return [f"a cycle between source files (one uses what the other defines): "
            f"{describe(component, edges)}"
            for component in cycles({a: set(bs) for a, bs in edges.items()})]


def main():
    if len(sys.argv) not in (2, 3):
        sys.exit(__doc__.split("\n\n")[1].strip())
    src = sys.argv[1]
    where, problems = source_files(src)
    graph, more = includes(src, where)
    problems += more + include_cycles(graph)
    if len(sys.argv) == 3:
        problems += symbol_cycles(sys.argv[2])
    for problem in problems:
        print(f"check_sources: {problem}")
    sys.exit(1 if problems else 0)


if __name__ == "__main__":
    main()
