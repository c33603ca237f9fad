//! Scenes shared by the workspace's integration tests.

use frames::Scene;

/// The uniform cantilever of length 1 along x (`mass_per_length = 1`,
/// `plastic_moment = 1`) with `n` elements, clamped at `A`, loaded at the
/// tip `B` by the force `fy`.
pub fn cantilever(n: usize, fy: f64) -> Scene {
    let src = format!(
        "[[node]]\nid = \"A\"\nx = 0.0\ny = 0.0\n[[node]]\nid = \"B\"\nx = 1.0\ny = 0.0\n\
         [[member]]\nid = \"AB\"\nfrom = \"A\"\nto = \"B\"\nplastic_moment = 1.0\nmass_per_length = 1.0\nelements = {n}\n\
         [[support]]\nnode = \"A\"\nfix = [\"x\", \"y\", \"rz\"]\n[[load]]\nnode = \"B\"\nfy = {fy:?}\n"
    );
    Scene::from_toml(&src, &format!("cantilever-{n}.toml")).expect("valid scene")
}
