//! Certification of frames paths (system (9), mixed form) by p-adic lifting
//! and by the fraction-free tableau gives the same certificate: the same
//! outcome, failing segment and exact breakpoints. The scenes cover
//! nonsingular free blocks (cantilever, pipe whip), singular ones whose
//! dependent rows keep an artificial variable (portal, two-storey), and the
//! stiff scenes whose f64 paths the certificate rejects. Only scenes the
//! tableau certifies in well under a second are used.

use frames::{Scene, System};
use plcp::exact::{certify_with, Engine};
use plcp::{Method, Settings};

#[test]
fn scenes_get_the_same_certificate_from_both_engines() {
    let root = concat!(env!("CARGO_MANIFEST_DIR"), "/scenes");
    let mut lifted = 0;
    for name in [
        "cantilever.toml",
        "cantilever-halftip.toml",
        "fixed-beam.toml",
        "portal-combined.toml",
        "portal-sway.toml",
        "two-storey.toml",
        "two-storey-sway.toml",
        "pipe-whip/straight.toml",
        "pipe-whip/restraint.toml",
        "stiff/extremes-chain.toml",
        "stiff/lengths-portal.toml",
        "stiff/symmetric-portal.toml",
    ] {
        let scene = Scene::from_file(format!("{root}/{name}")).expect("a shipped scene");
        let system = System::assemble(&scene.frame);
        let problem = system.plcp::<f64>(None).expect("system (9) is valid");
        let path = plcp::solve(&problem, &Settings::with_method(Method::Wolfe)).unwrap();
        let m = certify_with(&problem, &path, Engine::Modular);
        let b = certify_with(&problem, &path, Engine::Bareiss);
        assert_eq!(
            m.failure.as_ref().map(|f| f.segment),
            b.failure.as_ref().map(|f| f.segment),
            "{name}: modular {} / bareiss {}",
            m.summary(),
            b.summary()
        );
        assert_eq!(m.breakpoints, b.breakpoints, "{name}");
        assert_eq!(m.max_rel_diff.to_bits(), b.max_rel_diff.to_bits(), "{name}");
        assert_eq!(m.segments, b.segments, "{name}");
        lifted += m.modular;
    }
    assert!(lifted > 0, "no basis went through the lifting");
}
