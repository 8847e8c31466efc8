//! The pieces of USD text the animation is written in: prim names, points
//! and strings.

use std::collections::HashMap;

use hooke_core::Vec3;

/// Valid, distinct prim names: each name made a USD identifier
/// (`[A-Za-z_][A-Za-z0-9_]*`, other characters becoming `_`), a repeat
/// given `_2`, `_3` …
#[derive(Debug, Default)]
pub(super) struct Names {
    seen: HashMap<String, usize>,
}

impl Names {
    /// `name` as a prim name not given before.
    pub(super) fn unique(&mut self, name: &str) -> String {
        let mut base: String = name
            .chars()
            .map(|c| if c.is_ascii_alphanumeric() { c } else { '_' })
            .collect();
        if !base.starts_with(|c: char| c.is_ascii_alphabetic() || c == '_') {
            base.insert(0, '_');
        }
        let count = self.seen.entry(base.clone()).or_insert(0);
        *count += 1;
        let name = if *count == 1 {
            base
        } else {
            format!("{base}_{count}")
        };
        // A repeat's name may itself be taken ("a_2" given as a name).
        if *count > 1 && self.seen.contains_key(&name) {
            return self.unique(&name);
        }
        self.seen.entry(name.clone()).or_insert(1);
        name
    }
}

/// A point as USD writes a `point3f`: `(x, y, z)`, each coordinate rounded
/// to `f32` and written with the fewest digits that read back to it.
pub(super) fn point(p: Vec3) -> String {
    let [x, y, z] = [p.x, p.y, p.z].map(|c| c as f32);
    format!("({x}, {y}, {z})")
}

/// A point of `f64` coordinates: `(x, y, z)` with the fewest digits that
/// read back to each.
pub(super) fn point_f64(p: Vec3) -> String {
    format!("({}, {}, {})", p.x, p.y, p.z)
}

/// The corners of the box around `points` as their `f32` values, for a
/// prim's `extent`; a point at the origin when there are none.
pub(super) fn extent(points: &[Vec3]) -> [Vec3; 2] {
    let single = |p: &Vec3| p.map(|c| f64::from(c as f32));
    let mut low = points.first().map_or_else(Vec3::zeros, single);
    let mut high = low;
    for p in points.iter().map(single) {
        low = low.inf(&p);
        high = high.sup(&p);
    }
    [low, high]
}

/// `text` inside a USD string: quotes and backslashes escaped, line breaks
/// as `\n`.
pub(super) fn escaped(text: &str) -> String {
    text.replace('\\', "\\\\")
        .replace('"', "\\\"")
        .replace('\n', "\\n")
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn names_are_identifiers_and_distinct() {
        let mut names = Names::default();
        assert_eq!(names.unique("cloth"), "cloth");
        assert_eq!(names.unique("cloth"), "cloth_2");
        assert_eq!(names.unique("cloth_2"), "cloth_2_2");
        assert_eq!(names.unique("tet-mesh 1"), "tet_mesh_1");
        assert_eq!(names.unique("2 cloths"), "_2_cloths");
        assert_eq!(names.unique(""), "_");
    }

    #[test]
    fn points_are_written_as_their_single_precision_values() {
        let p = Vec3::new(0.1, -1.0 / 3.0, 1e-8);
        let text = point(p);
        assert_eq!(text, "(0.1, -0.33333334, 0.00000001)");
        let read: Vec<f32> = text
            .trim_matches(|c| c == '(' || c == ')')
            .split(", ")
            .map(|c| c.parse().unwrap())
            .collect();
        assert_eq!(read, [0.1_f32, -1.0 / 3.0, 1e-8]);
        assert_eq!(escaped("a \"b\"\n"), "a \\\"b\\\"\\n");
    }
}
