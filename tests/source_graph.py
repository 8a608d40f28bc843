#!/usr/bin/python3
"""No cycles between source files: the link graph of the C objects (A -> B when A's object
uses a symbol B's object defines, read with nm) and the import graph of the Python module
(A -> B when A imports B) must be acyclic, so that work flows down and a file never calls back
up into a file that calls it.

Usage: source_graph.py BUILD_DIR SOURCE_DIR [--show]
Prints each cycle (the files and the names that tie them) and exits 1 when there is one;
--show prints every edge. Exit 2 on bad usage (no objects found)."""
import ast
import collections
import glob
import os
import subprocess
import sys


def c_graph(build):
    """{source: {source it uses: [symbols]}} over the library's, the scene library's and the
    CLI's objects (each target on its own: a file compiled into two targets is one node)."""
    graphs = []
    for pattern in ('libcantact.so.*.p', 'libcantact_scene.a.p', 'cantact.p'):
        dirs = [d for d in glob.glob(os.path.join(build, pattern)) if os.path.isdir(d)]
        objs = sorted(o for d in dirs for o in glob.glob(os.path.join(d, '*.o')))
        if objs:
            graphs.append(objs)
    if not graphs:
        sys.exit('source_graph: no objects under %s (build first)' % build)
    objs = sorted(set(o for g in graphs for o in g))
    defs, uses = {}, collections.defaultdict(set)
    names = {}
    for o in objs:
        base = os.path.basename(o)[:-len('.o')]
        names[o] = source_name(base)
        out = subprocess.run(['nm', o], capture_output=True, text=True, check=True).stdout
        for line in out.splitlines():
            parts = line.split()
            if len(parts) == 3 and parts[1] in 'TDBRVWC':
                defs.setdefault(parts[2], names[o])
            elif len(parts) == 2 and parts[0] == 'U':
                uses[names[o]].add(parts[1])
    g = collections.defaultdict(dict)
    for a, syms in uses.items():
        for s in sorted(syms):
            b = defs.get(s)
            if b and b != a:
                g[a].setdefault(b, []).append(s)
    for n in names.values():
        g.setdefault(n, {})
    return g


def source_name(base):
    """src_surface_cantor.c -> src/surface/cantor.c: meson flattens the path with '_', so the
    real file is looked up among the candidates."""
    parts = base.split('_')
    # try every way of joining the parts with '/' or '_', shortest directories first
    def rec(i, acc):
        if i == len(parts):
            yield acc
            return
        for j in range(i + 1, len(parts) + 1):
            piece = '_'.join(parts[i:j])
            yield from rec(j, acc + [piece])
    for combo in rec(0, []):
        path = '/'.join(combo)
        if os.path.isfile(os.path.join(SOURCE, path)):
            return path
    return base


def py_graph(source):
    pkg = os.path.join(source, 'python', 'cantact')
    g = {}
    for path in sorted(glob.glob(os.path.join(pkg, '*.py'))):
        mod = os.path.basename(path)[:-3]
        with open(path, encoding='utf-8') as f:
            tree = ast.parse(f.read(), path)
        deps = {}
        for node in ast.walk(tree):
            if isinstance(node, ast.ImportFrom) and node.level == 1:
                if node.module:
                    deps.setdefault(node.module, []).extend(a.name for a in node.names)
                else:
                    for a in node.names:
                        deps.setdefault(a.name, []).append('*')
        g['python/cantact/%s.py' % mod] = {'python/cantact/%s.py' % m: n
                                           for m, n in deps.items()
                                           if m != mod and
                                           os.path.isfile(os.path.join(pkg, m + '.py'))}
    return g


def cycles(g):
    """The strongly connected components of more than one node (Tarjan, iterative)."""
    index, low, stack, on, out = {}, {}, [], set(), []
    counter = [0]
    for root in sorted(g):
        if root in index:
            continue
        work = [(root, iter(sorted(g[root])))]
        index[root] = low[root] = counter[0]
        counter[0] += 1
        stack.append(root)
        on.add(root)
        while work:
            v, it = work[-1]
            advanced = False
            for w in it:
                if w not in index:
                    index[w] = low[w] = counter[0]
                    counter[0] += 1
                    stack.append(w)
                    on.add(w)
                    work.append((w, iter(sorted(g.get(w, {})))))
                    advanced = True
                    break
                if w in on:
                    low[v] = min(low[v], index[w])
            if advanced:
                continue
            work.pop()
            if work:
                low[work[-1][0]] = min(low[work[-1][0]], low[v])
            if low[v] == index[v]:
                comp = []
                while True:
                    w = stack.pop()
                    on.discard(w)
                    comp.append(w)
                    if w == v:
                        break
                if len(comp) > 1:
                    out.append(sorted(comp))
    return out


def report(title, g, show):
    if show:
        for a in sorted(g):
            for b in sorted(g[a]):
                print('%s -> %s: %s' % (a, b, ' '.join(g[a][b][:6])))
    found = cycles(g)
    for comp in found:
        print('%s: a cycle of %d files:' % (title, len(comp)))
        for a in comp:
            for b in sorted(set(g[a]) & set(comp)):
                print('  %s -> %s: %s' % (a, b, ' '.join(g[a][b][:6])))
    return len(found)


if __name__ == '__main__':
    args = [a for a in sys.argv[1:] if not a.startswith('--')]
    if len(args) != 2:
        sys.exit(__doc__)
    build, SOURCE = args
    show = '--show' in sys.argv
    n = report('C link graph', c_graph(build), show) + report('Python imports', py_graph(SOURCE), show)
    if n:
        sys.exit(1)
    print('no cycle between source files (C objects and Python modules)')
