//! Contours of a function sampled on a rectangular grid, by marching
//! squares (Lorensen and Cline 1987, in two dimensions).
//!
//! The grid holds `f(x_j, y_i)` at the nodes of strictly increasing `x`
//! and `y`; a value may be NaN where `f` is undefined. A node is *above*
//! a level `c` when `f >= c`. Within a cell whose four corners are
//! defined, the level set is taken as straight segments between the
//! points where `f`, interpolated linearly along the cell's edges, equals
//! `c`: on an edge from `a` to `b` the crossing lies at the fraction
//! `(c - f_a) / (f_b - f_a)`, computed from the edge's lower node so that
//! the two cells sharing the edge place it bitwise alike. For a smooth
//! `f` the crossings lie within `h^2 max|f''| / (8 |grad f|)` of the true
//! level set (the linear interpolation error over an edge of length `h`),
//! and the segments within a chord's sagitta more.
//!
//! Contract:
//!
//! * A saddle cell (two diagonally opposite corners above, the other two
//!   below) is resolved by the mean of its corners, taken as the value at
//!   its centre: if the mean is above, the two above corners are joined
//!   and the segments cut off the two below corners; otherwise the
//!   segments cut off the above corners. Lines and regions use the same
//!   rule, so they agree, and no two segments cross.
//! * A cell with an undefined corner has no contour and no region: lines
//!   end on its edges (they are open there).
//! * [`lines`] joins the segments into polylines through shared edge
//!   crossings. A polyline is closed (last point equal to the first) when
//!   the level set is closed inside the defined cells; otherwise it runs
//!   from the grid's border, or an undefined cell, to another.
//! * [`region_at_least`] gives `{f >= c}` over the defined cells as
//!   counterclockwise polygons (in `x` right, `y` up): each cell's part,
//!   its boundary on the cell's edges and on the segments of [`lines`];
//!   runs of whole cells along a row are merged into one rectangle. The
//!   polygons only touch, so filling them together (one path, nonzero
//!   rule) covers the region without overlap or seam, and the regions at
//!   `c` of `f` and at `-c` of `-f` tile the defined cells (up to ties
//!   at saddles and at nodes equal to `c`).

/// Values on a rectangular grid: `values[i * xs.len() + j]` is `f(xs[j],
/// ys[i])`; `xs` and `ys` strictly increasing, at least two each.
#[derive(Debug, Clone, Copy)]
pub(crate) struct Grid<'a> {
    /// The nodes along `x`.
    pub xs: &'a [f64],
    /// The nodes along `y`.
    pub ys: &'a [f64],
    /// The values, row by row (`y` slowest); NaN where undefined.
    pub values: &'a [f64],
}

/// An edge of the grid: `(i, j, horizontal)`, from node `(i, j)` to
/// `(i, j + 1)` (horizontal) or to `(i + 1, j)` (vertical).
type Edge = (usize, usize, bool);

/// The corners of a cell counterclockwise from its lower left, as node
/// offsets `(di, dj)`, and the edges after each corner (edge `k` runs
/// from corner `k` to corner `k + 1`).
const CORNERS: [(usize, usize); 4] = [(0, 0), (0, 1), (1, 1), (1, 0)];

impl Grid<'_> {
    fn value(&self, i: usize, j: usize) -> f64 {
        self.values[i * self.xs.len() + j]
    }

    fn node(&self, i: usize, j: usize) -> (f64, f64) {
        (self.xs[j], self.ys[i])
    }

    /// The cell's edge `k` (see [`CORNERS`]) as a grid edge.
    fn edge(i: usize, j: usize, k: usize) -> Edge {
        match k {
            0 => (i, j, true),
            1 => (i, j + 1, false),
            2 => (i + 1, j, true),
            _ => (i, j, false),
        }
    }

    /// Where `f` crosses `level` on an edge whose ends lie on either side.
    fn crossing(&self, (i, j, horizontal): Edge, level: f64) -> (f64, f64) {
        let (i2, j2) = if horizontal { (i, j + 1) } else { (i + 1, j) };
        let (fa, fb) = (self.value(i, j), self.value(i2, j2));
        let t = (level - fa) / (fb - fa);
        let (a, b) = (self.node(i, j), self.node(i2, j2));
        (a.0 + t * (b.0 - a.0), a.1 + t * (b.1 - a.1))
    }

    /// The corner values of cell `(i, j)`, or `None` if one is undefined.
    fn corners(&self, i: usize, j: usize) -> Option<[f64; 4]> {
        let v = CORNERS.map(|(di, dj)| self.value(i + di, j + dj));
        v.iter().all(|x| !x.is_nan()).then_some(v)
    }

    fn cells(&self) -> impl Iterator<Item = (usize, usize)> {
        let (rows, cols) = (self.ys.len() - 1, self.xs.len() - 1);
        (0..rows).flat_map(move |i| (0..cols).map(move |j| (i, j)))
    }
}

/// The segments of one cell, each a pair of its edge indices (0..4).
fn cell_segments(v: [f64; 4], level: f64) -> Vec<(usize, usize)> {
    let above = v.map(|x| x >= level);
    let crossed: Vec<usize> = (0..4).filter(|&k| above[k] != above[(k + 1) % 4]).collect();
    match crossed[..] {
        [a, b] => vec![(a, b)],
        [_, _, _, _] => {
            // A saddle: cut off the corners of the kind the centre is not
            // (corner k lies between edges k - 1 and k).
            let centre_above = v.iter().sum::<f64>() / 4.0 >= level;
            (0..4)
                .filter(|&k| above[k] != centre_above)
                .map(|k| ((k + 3) % 4, k))
                .collect()
        }
        _ => Vec::new(),
    }
}

/// The contour lines of `grid` at `level` (module docs).
pub(crate) fn lines(grid: &Grid, level: f64) -> Vec<Vec<(f64, f64)>> {
    use std::collections::HashMap;
    let mut segments: Vec<[Edge; 2]> = Vec::new();
    for (i, j) in grid.cells() {
        if let Some(v) = grid.corners(i, j) {
            for (a, b) in cell_segments(v, level) {
                segments.push([Grid::edge(i, j, a), Grid::edge(i, j, b)]);
            }
        }
    }
    // Each crossed edge belongs to at most two cells, so to at most two
    // segments.
    let mut at: HashMap<Edge, Vec<usize>> = HashMap::new();
    for (s, ends) in segments.iter().enumerate() {
        for e in ends {
            at.entry(*e).or_default().push(s);
        }
    }
    let mut used = vec![false; segments.len()];
    let mut out = Vec::new();
    // Open lines first, from an end that only one segment has, then the
    // closed ones from any segment left.
    let mut starts: Vec<(usize, Edge)> = Vec::new();
    for (s, ends) in segments.iter().enumerate() {
        for e in ends {
            if at[e].len() == 1 {
                starts.push((s, *e));
            }
        }
    }
    starts.extend((0..segments.len()).map(|s| (s, segments[s][0])));
    for (first, from) in starts {
        if used[first] {
            continue;
        }
        let mut edges = vec![from];
        let (mut s, mut here) = (first, from);
        loop {
            used[s] = true;
            let [a, b] = segments[s];
            here = if a == here { b } else { a };
            edges.push(here);
            match at[&here].iter().find(|&&n| !used[n]) {
                Some(&n) => s = n,
                None => break,
            }
        }
        out.push(edges.iter().map(|e| grid.crossing(*e, level)).collect());
    }
    out
}

/// The region `{f >= level}` of `grid` as polygons (module docs).
pub(crate) fn region_at_least(grid: &Grid, level: f64) -> Vec<Vec<(f64, f64)>> {
    let mut out = Vec::new();
    // A run of whole cells in the current row: (row, first column, last).
    let mut run: Option<(usize, usize, usize)> = None;
    let flush = |run: &mut Option<(usize, usize, usize)>, out: &mut Vec<Vec<(f64, f64)>>| {
        if let Some((i, j0, j1)) = run.take() {
            let (x0, y0) = grid.node(i, j0);
            let (x1, y1) = grid.node(i + 1, j1 + 1);
            out.push(vec![(x0, y0), (x1, y0), (x1, y1), (x0, y1)]);
        }
    };
    for (i, j) in grid.cells() {
        if run.is_some_and(|(ri, _, rj)| ri != i || rj + 1 != j) {
            flush(&mut run, &mut out);
        }
        let Some(v) = grid.corners(i, j) else {
            continue;
        };
        let above = v.map(|x| x >= level);
        if above.iter().all(|&a| a) {
            run = Some(run.map_or((i, j, j), |(ri, j0, _)| (ri, j0, j)));
            continue;
        }
        flush(&mut run, &mut out);
        let node = |k: usize| grid.node(i + CORNERS[k].0, j + CORNERS[k].1);
        let cross = |k: usize| grid.crossing(Grid::edge(i, j, k), level);
        let saddle = above[0] == above[2] && above[1] == above[3] && above[0] != above[1];
        if saddle && v.iter().sum::<f64>() / 4.0 < level {
            // The centre is below: each above corner is a triangle of its
            // own, cut off by the segment between its two edges.
            for k in (0..4).filter(|&k| above[k]) {
                out.push(vec![cross((k + 3) % 4), node(k), cross(k)]);
            }
            continue;
        }
        // Walk the cell's border counterclockwise: the above corners and
        // the crossings between them.
        let mut polygon = Vec::new();
        for k in 0..4 {
            if above[k] {
                polygon.push(node(k));
            }
            if above[k] != above[(k + 1) % 4] {
                polygon.push(cross(k));
            }
        }
        if polygon.len() >= 3 {
            out.push(polygon);
        }
    }
    flush(&mut run, &mut out);
    out
}

/// Shoelace area of a polygon, positive counterclockwise: what the tests
/// of the contours and of the figures drawn from them measure.
#[cfg(test)]
pub(crate) fn area(polygon: &[(f64, f64)]) -> f64 {
    let n = polygon.len();
    (0..n)
        .map(|k| {
            let (a, b) = (polygon[k], polygon[(k + 1) % n]);
            a.0 * b.1 - b.0 * a.1
        })
        .sum::<f64>()
        / 2.0
}

#[cfg(test)]
mod tests {
    use super::*;

    /// `n` nodes spread evenly over `[a, b]`.
    fn nodes(a: f64, b: f64, n: usize) -> Vec<f64> {
        (0..n)
            .map(|k| a + (b - a) * k as f64 / (n - 1) as f64)
            .collect()
    }

    fn sample(xs: &[f64], ys: &[f64], f: impl Fn(f64, f64) -> f64) -> Vec<f64> {
        ys.iter()
            .flat_map(|&y| xs.iter().map(move |&x| (x, y)))
            .map(|(x, y)| f(x, y))
            .collect()
    }

    /// Whether the open segments `p q` and `r s` cross.
    fn cross(p: (f64, f64), q: (f64, f64), r: (f64, f64), s: (f64, f64)) -> bool {
        let side = |a: (f64, f64), b: (f64, f64), c: (f64, f64)| {
            (b.0 - a.0) * (c.1 - a.1) - (b.1 - a.1) * (c.0 - a.0)
        };
        side(p, q, r) * side(p, q, s) < 0.0 && side(r, s, p) * side(r, s, q) < 0.0
    }

    #[test]
    fn circle_contour_is_closed_and_within_the_interpolation_bound() {
        // f = x^2 + y^2 at level r^2: along an edge of length h the linear
        // interpolant of f is off by at most h^2 f''/8 = h^2/4, so a
        // crossing has |rho^2 - r^2| <= h^2/4, |rho - r| <= h^2/(8 r); a
        // chord of length <= sqrt(2) h sags at most (2 h^2)/(8 r) inside.
        let (r, n) = (0.7, 41);
        let xs = nodes(-1.0, 1.0, n);
        let h = 2.0 / (n - 1) as f64;
        let values = sample(&xs, &xs, |x, y| x * x + y * y);
        let grid = Grid {
            xs: &xs,
            ys: &xs,
            values: &values,
        };
        let found = lines(&grid, r * r);
        assert_eq!(found.len(), 1, "one closed curve");
        let line = &found[0];
        assert_eq!(line.first(), line.last(), "closed");
        assert!(line.len() > 40);
        let vertex_bound = h * h / (8.0 * r) * (1.0 + 1e-9);
        for p in line {
            assert!((p.0.hypot(p.1) - r).abs() <= vertex_bound, "{p:?}");
        }
        let chord_bound = vertex_bound + 2.0 * h * h / (8.0 * r);
        for w in line.windows(2) {
            let m = ((w[0].0 + w[1].0) / 2.0, (w[0].1 + w[1].1) / 2.0);
            assert!((m.0.hypot(m.1) - r).abs() <= chord_bound, "{m:?}");
        }
        // The error is O(h^2): it is far below the grid step itself.
        assert!(chord_bound < 0.05 * h);
    }

    #[test]
    fn disc_region_has_the_area_of_the_circle_to_the_interpolation_bound() {
        // {-(x^2 + y^2) >= -r^2} is the disc of area pi r^2; its boundary
        // is within the bound of the test above (3 h^2 / (8 r)) of the
        // circle, so the area within 2 pi r that much.
        let (r, n) = (0.6, 33);
        let xs = nodes(-1.0, 1.0, n);
        let h = 2.0 / (n - 1) as f64;
        let values = sample(&xs, &xs, |x, y| -(x * x + y * y));
        let grid = Grid {
            xs: &xs,
            ys: &xs,
            values: &values,
        };
        let polygons = region_at_least(&grid, -r * r);
        assert!(polygons.iter().all(|p| area(p) > 0.0), "counterclockwise");
        let total: f64 = polygons.iter().map(|p| area(p)).sum();
        let exact = std::f64::consts::PI * r * r;
        let bound = 2.0 * std::f64::consts::PI * r * 3.0 * h * h / (8.0 * r);
        assert!((total - exact).abs() <= bound, "{total} vs {exact}");
    }

    #[test]
    fn linear_field_gives_one_straight_contour() {
        // Linear interpolation of a linear f is exact: every crossing lies
        // on the line 0.3 x - 0.8 y + 0.1 = 0.05 to rounding, and the
        // contour runs from border to border.
        let xs = nodes(0.0, 2.0, 17);
        let ys = nodes(-1.0, 1.0, 13);
        let f = |x: f64, y: f64| 0.3 * x - 0.8 * y + 0.1;
        let values = sample(&xs, &ys, f);
        let grid = Grid {
            xs: &xs,
            ys: &ys,
            values: &values,
        };
        let found = lines(&grid, 0.05);
        assert_eq!(found.len(), 1);
        let line = &found[0];
        assert_ne!(line.first(), line.last(), "open");
        for p in line {
            assert!((f(p.0, p.1) - 0.05).abs() < 1e-14, "{p:?}");
        }
        let on_border = |p: &(f64, f64)| {
            [p.0 - 0.0, p.0 - 2.0, p.1 + 1.0, p.1 - 1.0]
                .iter()
                .any(|d| d.abs() < 1e-12)
        };
        assert!(on_border(&line[0]) && on_border(line.last().expect("points")));
    }

    #[test]
    fn linear_field_regions_of_f_and_minus_f_tile_the_grid() {
        // {f >= c} and {-f >= -c} = {f <= c} share only their boundary, so
        // their areas add up to the grid's (2 x 2 = 4) exactly to rounding.
        let xs = nodes(0.0, 2.0, 9);
        let ys = nodes(-1.0, 1.0, 7);
        let values = sample(&xs, &ys, |x, y| (x - 1.0).sin() + y * y * y);
        let negated: Vec<f64> = values.iter().map(|v| -v).collect();
        for c in [-0.5, 0.1, 0.7] {
            let up: f64 = region_at_least(
                &Grid {
                    xs: &xs,
                    ys: &ys,
                    values: &values,
                },
                c,
            )
            .iter()
            .map(|p| area(p))
            .sum();
            let down: f64 = region_at_least(
                &Grid {
                    xs: &xs,
                    ys: &ys,
                    values: &negated,
                },
                -c,
            )
            .iter()
            .map(|p| area(p))
            .sum();
            assert!((up + down - 4.0).abs() < 1e-12, "c = {c}: {up} + {down}");
        }
    }

    #[test]
    fn saddle_cell_is_resolved_by_its_centre_and_segments_never_cross() {
        // Corners 1, -1, 1, -1 counterclockwise from (0, 0): the above
        // corners (0, 0) and (1, 1) are diagonal. At level 0 the centre
        // (mean 0) is above: the region is one hexagon holding the centre,
        // of area 1 - 2 (1/2 * 1/2 * 1/2) = 3/4. At level 0.5 the centre
        // is below: two triangles at the above corners, each with legs
        // 1/4 (the crossing at (0.5 - 1) / (-1 - 1) = 1/4), area 1/32.
        let xs = [0.0, 1.0];
        let values = [1.0, -1.0, -1.0, 1.0];
        let grid = Grid {
            xs: &xs,
            ys: &xs,
            values: &values,
        };
        for (level, pieces, total) in [(0.0, 1, 0.75), (0.5, 2, 1.0 / 16.0)] {
            let segs = lines(&grid, level);
            assert_eq!(segs.len(), 2);
            assert!(!cross(segs[0][0], segs[0][1], segs[1][0], segs[1][1]));
            let region = region_at_least(&grid, level);
            assert_eq!(region.len(), pieces, "level {level}");
            let a: f64 = region.iter().map(|p| area(p)).sum();
            assert!((a - total).abs() < 1e-15, "level {level}: {a}");
        }
    }

    #[test]
    fn saddle_field_contours_do_not_cross() {
        // f = x y has its saddle at the origin, the centre of the middle
        // cell of an even number of nodes: the level sets of small c != 0
        // are two branches of a hyperbola, and at c = 0 the tie (mean 0)
        // joins the above quadrants; either way two lines that never
        // cross.
        let xs = nodes(-1.0, 1.0, 10);
        let values = sample(&xs, &xs, |x, y| x * y);
        let grid = Grid {
            xs: &xs,
            ys: &xs,
            values: &values,
        };
        for c in [-0.01, 0.0, 0.01] {
            let found = lines(&grid, c);
            assert_eq!(found.len(), 2, "c = {c}");
            for a in found[0].windows(2) {
                for b in found[1].windows(2) {
                    assert!(!cross(a[0], a[1], b[0], b[1]), "c = {c}");
                }
            }
        }
    }

    #[test]
    fn undefined_node_opens_the_contour_around_its_cells() {
        // The circle of the first test with f undefined at the node
        // (0.7, 0): the four cells around it have no contour, so the
        // circle becomes one open line whose ends lie on the border of
        // those cells, and no point lies inside them.
        let n = 41;
        let xs = nodes(-1.0, 1.0, n);
        let h = 2.0 / (n - 1) as f64;
        let mut values = sample(&xs, &xs, |x, y| x * x + y * y);
        let (i, j) = (20, 34);
        assert!((xs[j] - 0.7).abs() < 1e-12 && xs[i].abs() < 1e-12);
        values[i * n + j] = f64::NAN;
        let grid = Grid {
            xs: &xs,
            ys: &xs,
            values: &values,
        };
        let found = lines(&grid, 0.49);
        assert_eq!(found.len(), 1);
        let line = &found[0];
        assert_ne!(line.first(), line.last(), "open");
        let inside = |p: &(f64, f64)| (p.0 - 0.7).abs() < h - 1e-12 && p.1.abs() < h - 1e-12;
        assert!(!line.iter().any(inside));
        for end in [line[0], line[line.len() - 1]] {
            assert!((end.0 - 0.7).abs() <= h + 1e-12 && end.1.abs() <= h + 1e-12);
        }
        // The region leaves out the same four cells: the disc's area less
        // at most those cells' 4 h^2.
        let neg: Vec<f64> = values.iter().map(|v| -v).collect();
        let region: f64 = region_at_least(
            &Grid {
                xs: &xs,
                ys: &xs,
                values: &neg,
            },
            -0.49,
        )
        .iter()
        .map(|p| area(p))
        .sum();
        let disc = std::f64::consts::PI * 0.49;
        assert!(region < disc && region > disc - 4.0 * h * h - 3.0 * h * h);
    }
}
