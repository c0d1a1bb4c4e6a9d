/*
 * union_find.h: the root of a union-find forest (parent #N, roots point at
 * themselves), with path halving.  Shared by the modules that merge sets
 * (components, persistence, supernodes).
 */
#ifndef PS_UNION_FIND_H
#define PS_UNION_FIND_H

static inline int ps_union_find_root(int *parent, int v) {
    while (parent[v] != v) v = parent[v] = parent[parent[v]];
    return v;
}

#endif
