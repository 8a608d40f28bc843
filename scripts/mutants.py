#!/usr/bin/python3
"""The mutation check: applies each deliberate mistake of tests/mutants/*.mut, one at a time, to
a scratch copy of the tree and asks the unit suites to catch it.

A rule names the suites that should kill it (`suites: rod, bundle`), or one test of a suite
(`suites: cli/hostile-cli`: only that test, where the suite's faster tests cannot catch it). Those run first, each test
stopping at its first failed check (cmocka's CMOCKA_TEST_ABORT, the shell tests' CT_FAIL_FAST),
and the first red test kills the mutant. Only when they all pass do the remaining suites run; a
mutant killed there is reported as "killed, but not by its suites" and fails the run, so the
`suites:` lines stay honest. A mutant no test catches, a rule whose old text is not found once
in its file (stale), and a rule without `suites:` fail the run too.

Independent mutants run in parallel on separate scratch trees (--jobs, default 2: measured
faster than one tree on two cores, see docs/benchmarks.md).

Usage: scripts/mutants [--jobs N] [RULE.mut ...]     run the rules (default: all)
       scripts/mutants --check [RULE.mut ...]         every rule applies and names known suites
       scripts/mutants --matrix [RULE.mut ...]        which tests kill each rule (every test run)
Options of a run: --no-baseline: the unmutated tree's tests are not run first (CI: scripts/test
has just run them on the same code); --within SUITE,...: only those suites' tests exist for the
run (the check's self-test, whose survivor would otherwise walk every test).
Exit status: 0 every rule killed by its suites, 1 otherwise, 2 a malformed rule or bad usage.
"""
import json
import os
import queue
import random
import shutil
import subprocess
import sys
import tempfile
import threading
import time

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
RULE_DIR = os.path.join(ROOT, 'tests', 'mutants')
KEYS = ('why', 'file', 'old', 'new', 'suites')
# Suites the mutation check never runs: slow checks (scripts/test runs them once, release only)
EXCLUDED_SUITES = {'slow'}


class RuleError(Exception):
    pass


def parse_rule(path, need_suites=True):
    """The rule's keys; RuleError names the file and what is wrong."""
    spec = {}
    with open(path, encoding='utf-8') as f:
        for n, line in enumerate(f, 1):
            line = line.rstrip('\n')
            if not line.strip():
                continue
            if ': ' not in line:
                raise RuleError('%s:%d: expected "key: value"' % (path, n))
            k, v = line.split(': ', 1)
            if k not in KEYS:
                raise RuleError('%s:%d: unknown key %r (keys: %s)' % (path, n, k, ', '.join(KEYS)))
            if k in spec:
                raise RuleError('%s:%d: %s given twice' % (path, n, k))
            spec[k] = v
    if not need_suites:
        spec.setdefault('suites', 'none')
    for k in KEYS:
        if k not in spec:
            hint = ' (name the suites that should kill it)' if k == 'suites' else ''
            raise RuleError('%s: no "%s:" line%s' % (path, k, hint))
    for k in ('old', 'new'):  # \n in a rule stands for a line break
        spec[k] = spec[k].replace('\\n', '\n')
    spec['suites'] = [s.strip() for s in spec['suites'].split(',') if s.strip()]
    if not spec['suites']:
        raise RuleError('%s: "suites:" names no suite' % path)
    spec['name'] = os.path.basename(path)[:-4] if path.endswith('.mut') else os.path.basename(path)
    spec['path'] = path
    return spec


def apply_rule(rule, text):
    """The mutated text, or None when the old text does not occur exactly once."""
    if text.count(rule['old']) != 1:
        return None
    return text.replace(rule['old'], rule['new'])


def stale_message(rule, tree):
    path = os.path.join(tree, rule['file'])
    if not os.path.exists(path):
        return '%s: its file %s does not exist' % (rule['name'], rule['file'])
    with open(path, encoding='utf-8') as f:
        n = f.read().count(rule['old'])
    return '%s: its old text occurs %d times in %s (must be once)' % (rule['name'], n, rule['file'])


def load_tests(build):
    """The unit tests of a configured build, by suite; the slow suites left out."""
    out = subprocess.run(['meson', 'introspect', '--tests', build], check=True,
                         capture_output=True, text=True).stdout
    targets = json.loads(subprocess.run(['meson', 'introspect', '--targets', build], check=True,
                                        capture_output=True, text=True).stdout)
    files = {t['id']: [os.path.relpath(f, build) for f in t['filename']] for t in targets}
    tests = []
    for t in json.loads(out):
        suites = [s.split(':', 1)[-1] for s in t['suite']]
        if EXCLUDED_SUITES & set(suites):
            continue
        t['suites'] = suites
        t['id'] = '%s/%s' % (suites[0], t['name'])  # names repeat across suites
        t['targets'] = [f for d in t['depends'] for f in files.get(d, [])]
        tests.append(t)
    return tests


def configured_build():
    """A configured build directory of the working tree (for --check), set up if there is none."""
    build = os.path.join(ROOT, 'build')
    if os.path.exists(os.path.join(build, 'meson-info', 'intro-tests.json')):
        return build, None
    tmp = tempfile.mkdtemp(prefix='cantact-mutants-')
    subprocess.run(['meson', 'setup', os.path.join(tmp, 'b'), ROOT, '-Dtests=true'], check=True,
                   stdout=subprocess.DEVNULL)
    return os.path.join(tmp, 'b'), tmp


def known_names(tests):
    """What a rule's suites: line may name: a suite, or one test of a suite as SUITE/TEST."""
    return ({s for t in tests for s in t['suites']} |
            {'%s/%s' % (s, t['name']) for t in tests for s in t['suites']})


def names_test(name, t):
    """1 when the suites: entry name (SUITE or SUITE/TEST) takes the test t."""
    suite, _, test = name.partition('/')
    return suite in t['suites'] and (not test or test == t['name'])


def check_rules(rules, tree, known_suites):
    """(stale messages, unknown-suite messages) for the rules against the tree's files."""
    stale, unknown = [], []
    for r in rules:
        path = os.path.join(tree, r['file'])
        text = open(path, encoding='utf-8').read() if os.path.exists(path) else ''
        if apply_rule(r, text) is None:
            stale.append(stale_message(r, tree))
        bad = [s for s in r['suites'] if s not in known_suites]
        if bad:
            unknown.append('%s: unknown suite %s (suites: %s)' % (
                r['path'], ', '.join(bad), ', '.join(sorted(known_suites))))
    return stale, unknown


class Tree:
    """A scratch copy of the tracked files with its own configured, built build directory."""

    def __init__(self, base, index):
        self.src = os.path.join(base, 't%d' % index)
        self.build = os.path.join(self.src, 'build')
        # tracked files and new ones not ignored: a developer's uncommitted work is checked too
        files = subprocess.run(['git', '-C', ROOT, 'ls-files', '-z', '--cached', '--others',
                                '--exclude-standard'], check=True,
                               capture_output=True).stdout.split(b'\0')
        for f in files:
            if not f:
                continue
            f = f.decode()
            src = os.path.join(ROOT, f)
            if not os.path.lexists(src):  # deleted in the working tree, not yet committed
                continue
            dst = os.path.join(self.src, f)
            os.makedirs(os.path.dirname(dst), exist_ok=True)
            shutil.copy2(src, dst, follow_symlinks=False)

    def setup(self, within=None):
        subprocess.run(['meson', 'setup', self.build, self.src, '-Dtests=true'], check=True,
                       stdout=subprocess.DEVNULL)
        self.ninja([])
        self.tests = [t for t in load_tests(self.build)  # their commands point into this tree
                      if not within or set(t['suites']) & within]

    def ninja(self, targets):
        """True when the targets (all when empty) build."""
        r = subprocess.run(['ninja', '-C', self.build] + targets, stdout=subprocess.DEVNULL,
                           stderr=subprocess.DEVNULL)
        return r.returncode == 0

    def run_test(self, t, timeout):
        """True when the test passes. The tests' own paths point into this tree."""
        env = dict(os.environ)
        env.update(t['env'])
        env['MALLOC_PERTURB_'] = env.get('MALLOC_PERTURB_', str(random.randint(1, 255)))
        env['CMOCKA_TEST_ABORT'] = '1'  # cmocka: abort at the first failed check
        env['CT_FAIL_FAST'] = '1'  # the shell tests: exit at the first failed check
        env['PYTEST_ADDOPTS'] = '-x'  # pytest: stop at the first failed test
        try:
            r = subprocess.run(t['cmd'], env=env, cwd=t['workdir'] or self.build,
                               stdin=subprocess.DEVNULL, stdout=subprocess.DEVNULL,
                               stderr=subprocess.DEVNULL, timeout=timeout)
        except subprocess.TimeoutExpired:
            return False
        return r.returncode == 0


def test_timeout(t, durations):
    # a mutant that loops is killed by the clock: ten times the clean run, at least 30 s (a test
    # whose clean run is not known: 60 s)
    return min(t['timeout'] or 300, max(30.0, 10 * durations.get(t['id'], 6.0)))


def logged_durations():
    """The tests' durations of the last `meson test` of the working tree's build (its
    testlog.json), by suite/name: what --no-baseline times mutants by. {} when there is none."""
    out = {}
    try:
        with open(os.path.join(ROOT, 'build', 'meson-logs', 'testlog.json')) as f:
            for line in f:
                r = json.loads(line)
                name = r['name'].split(':', 1)[-1].replace(' / ', '/')
                if r.get('result') == 'OK':
                    out[name] = float(r['duration'])
    except (OSError, ValueError, KeyError):
        return {}
    return out


def run_mutant(tree, rule, durations, matrix):
    """(verdict, detail) for one rule on one tree; the tree's file is restored afterwards."""
    path = os.path.join(tree.src, rule['file'])
    original = open(path, encoding='utf-8').read()
    mutated = apply_rule(rule, original)
    if mutated is None:
        return 'stale', stale_message(rule, tree.src)
    try:
        with open(path, 'w', encoding='utf-8') as f:
            f.write(mutated)
        by_speed = sorted(tree.tests, key=lambda t: durations.get(t['id'], 0.0))
        if matrix:
            if not tree.ninja([]):
                return 'matrix', 'does not build'
            killers = [t for t in by_speed if not tree.run_test(t, test_timeout(t, durations))]
            return 'matrix', ' '.join('%s/%s' % (t['suites'][0], t['name']) for t in killers)
        named = []
        for s in rule['suites']:
            named += [t for t in by_speed if names_test(s, t) and t not in named]
        targets = sorted({f for t in named for f in t['targets']})
        if not tree.ninja(targets):
            return 'killed', 'does not build'
        for t in named:
            if not tree.run_test(t, test_timeout(t, durations)):
                return 'killed', 'by %s/%s' % (t['suites'][0], t['name'])
        if not tree.ninja([]):
            return 'mislabelled', 'killed, but not by its suites: only the full build fails'
        for t in by_speed:
            if t not in named and not tree.run_test(t, test_timeout(t, durations)):
                return 'mislabelled', 'killed, but not by its suites (%s): by %s/%s' % (
                    ', '.join(rule['suites']), t['suites'][0], t['name'])
        return 'survived', rule['why']
    finally:
        with open(path, 'w', encoding='utf-8') as f:
            f.write(original)


def main(argv):
    mode, jobs, paths = 'run', 2, []
    baseline, within = True, None
    args = list(argv)
    while args:
        a = args.pop(0)
        if a == '--no-baseline':
            baseline = False
        elif a == '--within':
            if not args or not args[0].strip(','):
                print('mutants: --within needs SUITE,...', file=sys.stderr)
                return 2
            within = {x.strip() for x in args.pop(0).split(',') if x.strip()}
        elif a == '--check':
            mode = 'check'
        elif a == '--matrix':
            mode = 'matrix'
        elif a == '--jobs':
            if not args or not args[0].isdigit() or int(args[0]) < 1:
                print('mutants: --jobs needs a positive integer', file=sys.stderr)
                return 2
            jobs = int(args.pop(0))
        elif a in ('-h', '--help'):
            print(__doc__.strip())
            return 0
        elif a.startswith('-'):
            print('mutants: unknown option %s (see --help)' % a, file=sys.stderr)
            return 2
        else:
            paths.append(a)
    if not paths:
        paths = sorted(os.path.join(RULE_DIR, f) for f in os.listdir(RULE_DIR)
                       if f.endswith('.mut'))
    try:
        rules = [parse_rule(p, need_suites=mode != 'matrix') for p in paths]
    except (RuleError, OSError) as e:
        print('mutants: %s' % e, file=sys.stderr)
        return 2

    t0 = time.time()
    if mode == 'check':
        build, tmp = configured_build()
        try:
            known = known_names(load_tests(build))
        finally:
            if tmp:
                shutil.rmtree(tmp)
        stale, unknown = check_rules(rules, ROOT, known)
        for m in unknown:
            print('mutants: %s' % m, file=sys.stderr)
        for m in stale:
            print('stale: %s' % m)
        ok = not stale and not unknown
        print('%d rules checked in %.1f s: %s' % (len(rules), time.time() - t0,
                                                 'all apply' if ok else 'NOT all apply'))
        return 0 if ok else (2 if unknown else 1)

    base = tempfile.mkdtemp(prefix='cantact-mutants-')
    try:
        return run(rules, base, jobs, mode == 'matrix', t0, baseline, within)
    finally:
        shutil.rmtree(base, ignore_errors=True)


def run(rules, base, jobs, matrix, t0, baseline=True, within=None):
    jobs = max(1, min(jobs, len(rules)))
    trees = [Tree(base, i) for i in range(jobs)]
    trees[0].setup(within)
    tests = trees[0].tests
    known = known_names(tests)
    stale, unknown = check_rules(rules, trees[0].src, known)
    if unknown and not matrix:
        for m in unknown:
            print('mutants: %s' % m, file=sys.stderr)
        return 2
    for m in stale:
        print('stale: %s' % m, flush=True)
    stale_names = {m.split(':', 1)[0] for m in stale}
    todo = [r for r in rules if r['name'] not in stale_names]

    # The other trees build while the first runs every test on the unmutated code: a red test
    # there would kill every mutant, so it stops the run; its times order the tests.
    setups = [threading.Thread(target=t.setup, args=(within,)) for t in trees[1:]]
    for s in setups:
        s.start()
    durations = {} if baseline else logged_durations()
    broken = []
    for t in tests if baseline else []:
        s = time.time()
        if not trees[0].run_test(t, t['timeout'] or 300):
            broken.append(t['id'])
        durations[t['id']] = time.time() - s
    for s in setups:
        s.join()
    if broken:
        print('mutants: the unmutated tree fails %s: fix that first' % ', '.join(broken),
              file=sys.stderr)
        return 1
    if baseline:
        print('baseline: %d tests pass on the unmutated tree (%.1f s); %d rules on %d tree%s' % (
            len(tests), sum(durations.values()), len(todo), jobs, 's' if jobs > 1 else ''),
            flush=True)
    else:
        print('baseline not run (--no-baseline); %d tests; %d rules on %d tree%s' % (
            len(tests), len(todo), jobs, 's' if jobs > 1 else ''), flush=True)

    work = queue.Queue()
    for r in todo:
        work.put(r)
    results = []
    lock = threading.Lock()

    def worker(tree):
        while True:
            try:
                r = work.get_nowait()
            except queue.Empty:
                return
            s = time.time()
            verdict, detail = run_mutant(tree, r, durations, matrix)
            with lock:
                results.append((r, verdict, detail))
                label = {'killed': 'killed', 'mislabelled': 'MISLABELLED', 'survived': 'SURVIVED',
                         'stale': 'STALE', 'matrix': 'killers'}[verdict]
                print('%s: %s (%s) [%.1f s]' % (label, r['name'], detail, time.time() - s),
                      flush=True)

    threads = [threading.Thread(target=worker, args=(t,)) for t in trees]
    for t in threads:
        t.start()
    for t in threads:
        t.join()

    if matrix:
        print('matrix of %d rules in %.0f s' % (len(results), time.time() - t0))
        return 0
    killed = sum(1 for _, v, _ in results if v in ('killed', 'mislabelled'))
    print('killed %d of %d in %.0f s (%d tree%s)' % (killed, len(rules), time.time() - t0, jobs,
                                                   's' if jobs > 1 else ''))
    order = {r['name']: i for i, r in enumerate(rules)}
    results.sort(key=lambda x: order[x[0]['name']])
    for r, v, d in results:
        if v == 'survived':
            print('survivor: %s: %s' % (r['name'], d))
        elif v == 'mislabelled':
            print('mislabelled: %s: %s' % (r['name'], d))
        elif v == 'stale':
            stale.append(d)
    for m in stale:
        print('stale: %s' % m)
    bad = [v for _, v, _ in results if v != 'killed']
    return 0 if not bad and not stale else 1


if __name__ == '__main__':
    sys.exit(main(sys.argv[1:]))
