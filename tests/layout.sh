#!/bin/sh
# layout.sh: checks the source layout the docs describe (README, "Layout"):
#   - core/'s folders depend one way: util, graph, features, hierarchy,
#     refine, then the driver at the top of core/ (pointseg.h, the public
#     header, any folder may include);
#   - a header marked "PRIVATE to" is included only from its own folder
#     (and that folder's unit tests, tests/unit/FOLDER/, which are white-box),
#     and within core/ only by the files its opening comment names (and its
#     own .c);
#   - no header includes itself through others (no include cycles);
#   - api/, server/ and clients/ include only core's public header.
# Prints PASS/FAIL lines (tests/run.sh counts them).
cd "$(dirname "$0")/.." || exit 1
python3 - <<'PY'
import glob, os, re, sys
order = ['util', 'graph', 'features', 'hierarchy', 'refine', 'top']
inc = re.compile(r'^#include "([^"]+)"', re.M)
def folder(path):
    parts = path.split('/')
    return parts[1] if len(parts) == 3 else 'top'
def report(name, problems):
    for p in problems: print('    ' + p)
    print(('PASS' if not problems else 'FAIL') + ' layout.sh:' + name)
core = sorted(glob.glob('core/*.[ch]') + glob.glob('core/*/*.[ch]'))
includes = {p: inc.findall(open(p).read()) for p in core}
def resolve(name):
    p = 'core/' + name
    return p if os.path.exists(p) else None
bad = []
for p, names in includes.items():
    for n in names:
        q = resolve(n)
        if q and order.index(folder(q)) > order.index(folder(p)) and n != 'pointseg.h':
            bad.append('%s includes %s (a later phase)' % (p, n))
report('folders_depend_one_way', bad)
private = [h for h in core if h.endswith('.h') and 'PRIVATE to' in open(h).read(600)]
bad = []
for h in private:
    home = os.path.dirname(h)
    tests = 'tests/unit' + home[len('core'):]
    for p in glob.glob('**/*.[ch]', recursive=True):
        if p.startswith('build/') or os.path.dirname(p) in (home, tests): continue
        if os.path.relpath(h, 'core') in inc.findall(open(p).read()):
            bad.append('%s includes %s, private to %s/' % (p, h, home))
report('private_headers_stay_home', bad)
# Within its folder too: a private header's opening comment names the
# files it is private to, and only they (its own .c and the folder's unit
# tests aside) include it.
bad = []
for h in private:
    text = open(h).read()
    opening = text[:text.index('*/')].split('\n *\n')[0]
    named = set(re.findall(r'\b([a-z_]+\.[ch])\b', opening)) - {os.path.basename(h)}
    own = os.path.basename(h)[:-2] + '.c'
    for p in core:
        if p == h or os.path.basename(p) in named or os.path.basename(p) == own: continue
        if os.path.relpath(h, 'core') in includes[p]:
            bad.append('%s includes %s, which names only %s' % (p, h, ', '.join(sorted(named))))
report('private_headers_name_their_includers', bad)
bad = []
graph = {h: [resolve(n) for n in includes[h] if resolve(n)] for h in core if h.endswith('.h')}
def walk(h, stack, seen):
    if h in stack: bad.append(' -> '.join(stack[stack.index(h):] + [h])); return
    if h in seen: return
    seen.add(h)
    for d in graph.get(h, []): walk(d, stack + [h], seen)
seen = set()
for h in graph: walk(h, [], seen)
report('no_include_cycles', bad)
bad = []
for p in glob.glob('api/**/*.[ch]', recursive=True) + glob.glob('server/*.[ch]') + \
         glob.glob('clients/**/*.[ch]', recursive=True):
    for n in inc.findall(open(p).read()):
        if resolve(n) and n != 'pointseg.h': bad.append('%s includes core/%s' % (p, n))
report('outer_layers_see_the_public_header_only', bad)
PY
