#include "ordering/cuthill_mckee.h"

#include <algorithm>
#include <utility>

namespace ode_bpp::ordering {

namespace {

/// Breadth-first level structure rooted at root (its whole component): leaves the visit order
/// in queue, the index in queue where the deepest level starts in last_level_begin, and returns
/// the number of levels. level[] must be all -1 on entry and is restored to that on exit.
int level_structure(const Graph& g, int root, std::vector<int>& level, std::vector<int>& queue,
                    std::size_t& last_level_begin) {
    queue.clear();
    queue.push_back(root);
    level[root] = 0;
    last_level_begin = 0;
    for (std::size_t head = 0; head < queue.size(); ++head) {
        const int v = queue[head];
        if (level[v] != level[queue[last_level_begin]]) last_level_begin = head;
        for (int e = g.xadj[v]; e < g.xadj[v + 1]; ++e) {
            const int w = g.adj[e];
            if (level[w] >= 0) continue;
            level[w] = level[v] + 1;
            queue.push_back(w);
        }
    }
    const int depth = level[queue.back()] + 1;
    for (int v : queue) level[v] = -1;
    return depth;
}

int min_degree_vertex(const Graph& g, const std::vector<int>& vertices, std::size_t begin) {
    int best = vertices[begin];
    for (std::size_t idx = begin; idx < vertices.size(); ++idx) {
        const int v = vertices[idx];
        if (g.degree(v) < g.degree(best) || (g.degree(v) == g.degree(best) && v < best)) best = v;
    }
    return best;
}

/// George & Liu: from a minimal-degree vertex of the component, jump to a minimal-degree vertex
/// of the deepest level while that increases the eccentricity.
int pseudo_peripheral_vertex(const Graph& g, int seed, std::vector<int>& level, std::vector<int>& queue) {
    std::size_t last_level_begin = 0;
    level_structure(g, seed, level, queue, last_level_begin);
    int root = min_degree_vertex(g, queue, 0);
    int depth = level_structure(g, root, level, queue, last_level_begin);
    while (true) {
        const int candidate = min_degree_vertex(g, queue, last_level_begin);
        std::vector<int> candidate_queue;
        std::size_t candidate_last = 0;
        const int candidate_depth = level_structure(g, candidate, level, candidate_queue, candidate_last);
        if (candidate_depth <= depth) return root;
        root = candidate;
        depth = candidate_depth;
        queue = std::move(candidate_queue);
        last_level_begin = candidate_last;
    }
}

/// Cuthill-McKee breadth-first numbering of root's component, appended to order.
void number_component(const Graph& g, int root, std::vector<char>& numbered, std::vector<int>& order) {
    std::size_t head = order.size();
    order.push_back(root);
    numbered[root] = 1;
    std::vector<int> fresh;
    for (; head < order.size(); ++head) {
        const int v = order[head];
        fresh.clear();
        for (int e = g.xadj[v]; e < g.xadj[v + 1]; ++e)
            if (!numbered[g.adj[e]]) fresh.push_back(g.adj[e]);
        std::sort(fresh.begin(), fresh.end(), [&g](int a, int b) {
            return std::make_pair(g.degree(a), a) < std::make_pair(g.degree(b), b);
        });
        for (int w : fresh) {
            numbered[w] = 1;
            order.push_back(w);
        }
    }
}

}  // namespace

std::vector<int> cuthill_mckee(const Graph& g, bool reverse) {
    const int n = g.n();
    std::vector<int> order;
    order.reserve(static_cast<std::size_t>(n));
    std::vector<char> numbered(static_cast<std::size_t>(n), 0);
    std::vector<int> level(static_cast<std::size_t>(n), -1);
    std::vector<int> queue;
    for (int seed = 0; seed < n; ++seed) {
        if (numbered[seed]) continue;
        const int root = pseudo_peripheral_vertex(g, seed, level, queue);
        number_component(g, root, numbered, order);
    }
    if (reverse) std::reverse(order.begin(), order.end());
    return order;
}

}  // namespace ode_bpp::ordering
