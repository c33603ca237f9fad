//! The command line: bad scenes end with exit code 2 and one line naming file,
//! line and key; `export` prints plcp's JSON; `run --json` has the contract's keys.

use std::process::Command;

fn frames() -> Command {
    Command::new(env!("CARGO_BIN_EXE_frames"))
}

fn scenes() -> std::path::PathBuf {
    std::path::Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("..")
        .join("scenes")
}

const GOOD: &str = r#"[[node]]
id = "A"
x = 0.0
y = 0.0
[[node]]
id = "B"
x = 1.0
y = 0.0
[[member]]
id = "AB"
from = "A"
to = "B"
plastic_moment = 1.0
elements = 2
mass_per_length = 1.0
[[support]]
node = "A"
fix = ["x", "y", "rz"]
[[load]]
node = "B"
fy = -1.0
[history]
kind = "ramp"
rate = 1.0
"#;

fn bad(name: &str, src: &str) -> (i32, String) {
    bad_bytes(name, src.as_bytes())
}

fn bad_bytes(name: &str, src: &[u8]) -> (i32, String) {
    let dir = std::env::temp_dir().join(format!("frames-cli-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let file = dir.join(name);
    std::fs::write(&file, src).unwrap();
    let out = frames().arg("run").arg(&file).output().unwrap();
    let err = String::from_utf8_lossy(&out.stderr).to_string();
    assert!(out.stdout.is_empty(), "{name}: stdout not empty");
    assert_eq!(err.trim_end().lines().count(), 1, "{name}: {err}");
    assert!(err.contains(&file.display().to_string()), "{name}: {err}");
    (out.status.code().unwrap_or(-1), err)
}

#[test]
fn scene_errors_name_file_line_and_key() {
    let cases: Vec<(&str, String, &str)> = vec![
        (
            "unknown-node.toml",
            GOOD.replace("to = \"B\"", "to = \"Q\""),
            ":12: member \"AB\" to: unknown node \"Q\"",
        ),
        (
            "duplicate.toml",
            GOOD.replace("id = \"B\"", "id = \"A\""),
            ":6: node \"A\" id: duplicate node id",
        ),
        (
            "zero-length.toml",
            GOOD.replace("x = 1.0", "x = 0.0"),
            ":12: member \"AB\" to: member of zero length",
        ),
        (
            "massless.toml",
            GOOD.replace("mass_per_length = 1.0", "mass_per_length = 0.0"),
            ":21: load \"B\" fy: the load acts on a mechanism with no mass",
        ),
        (
            "decreasing.toml",
            GOOD.replace(
                "kind = \"ramp\"\nrate = 1.0",
                "kind = \"table\"\npoints = [[0.0, 0.0], [1.0, 2.0], [2.0, 1.0]]",
            ),
            ":24: history points: decreasing history",
        ),
        (
            "nan.toml",
            GOOD.replace("plastic_moment = 1.0", "plastic_moment = nan"),
            ":13: member \"AB\" plastic_moment: must be a finite number",
        ),
        (
            "typo.toml",
            GOOD.replace("plastic_moment", "plastic_momnet"),
            ":13:1: plastic_momnet: unknown key \"plastic_momnet\": the accepted keys are `id`,",
        ),
        (
            "syntax.toml",
            GOOD.replace("y = 0.0\n[[member]]", "y = \n[[member]]"),
            ":8:5: y: ",
        ),
        (
            "negative-rate.toml",
            GOOD.replace("rate = 1.0", "rate = -1.0"),
            ":24: history rate: must be positive",
        ),
    ];
    for (name, src, want) in cases {
        let (code, err) = bad(name, &src);
        assert_eq!(code, 2, "{name}: {err}");
        assert!(err.contains(want), "{name}: expected '{want}' in: {err}");
    }
    let out = frames()
        .args(["run", "/no/such/scene.toml"])
        .output()
        .unwrap();
    assert_eq!(out.status.code(), Some(2));
    let out = frames()
        .args(["run"])
        .arg(scenes().join("cantilever.toml"))
        .args(["--precision", "f16"])
        .output()
        .unwrap();
    assert_eq!(out.status.code(), Some(2));
}

/// Unknown keys name the key, line, column and the accepted keys; a `comment`
/// key (any value) is accepted in every table; bytes that are not UTF-8 are an
/// error naming where they are (the scene was read with `read_to_string`,
/// whose error gave no position).
#[test]
fn strict_keys_comments_and_utf8() {
    let (code, err) = bad(
        "indented.toml",
        &GOOD.replace("rate = 1.0", "  rate = 1.0\n  rtae = 2.0"),
    );
    assert_eq!(code, 2, "{err}");
    assert!(
        err.contains(":25:3: rtae: unknown key \"rtae\": the accepted keys are `kind`, `rate`,")
            && err.contains("`comment`"),
        "{err}"
    );
    let noted = GOOD
        .replace("[[node]]\n", "[[node]]\ncomment = \"a joint\"\n")
        .replace(
            "[history]\n",
            "[history]\ncomment = { source = \"test\", rate = 9 }\n",
        );
    let dir = std::env::temp_dir().join(format!("frames-cli-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let file = dir.join("noted.toml");
    std::fs::write(&file, format!("comment = [\"top\", 1]\n{noted}")).unwrap();
    let out = frames().arg("run").arg(&file).output().unwrap();
    assert_eq!(
        out.status.code(),
        Some(0),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    let mut latin1 = b"# r\xe9sum\xe9 of the scene\n".to_vec();
    latin1.extend_from_slice(GOOD.as_bytes());
    let (code, err) = bad_bytes("latin1.toml", &latin1);
    assert_eq!(code, 2, "{err}");
    assert!(
        err.contains(":1:4: (encoding): invalid UTF-8 at byte offset 3: byte 0xE9"),
        "{err}"
    );
}

#[test]
fn lemke_refuses_an_indeterminate_frame_with_plcps_message() {
    let out = frames()
        .arg("run")
        .arg(scenes().join("portal-sway.toml"))
        .args(["--method", "lemke"])
        .output()
        .unwrap();
    assert_eq!(out.status.code(), Some(2));
    let err = String::from_utf8_lossy(&out.stderr);
    assert!(err.contains("singular"), "{err}");
    assert_eq!(err.trim_end().lines().count(), 1);
}

#[test]
fn json_has_the_contract_keys() {
    for extra in [&[][..], &["--method", "lemke", "--precision", "f128"][..]] {
        let out = frames()
            .arg("run")
            .arg(scenes().join("cantilever.toml"))
            .arg("--json")
            .args(extra)
            .output()
            .unwrap();
        assert!(
            out.status.success(),
            "{}",
            String::from_utf8_lossy(&out.stderr)
        );
        let v: serde_json::Value = serde_json::from_slice(&out.stdout).unwrap();
        for k in [
            "system",
            "status",
            "breakpoints",
            "hinges",
            "intervals",
            "moments_at_breakpoints",
            "response",
        ] {
            assert!(v.get(k).is_some(), "missing {k}");
        }
        assert_eq!(v["system"]["free"], 16);
        assert_eq!(v["system"]["complementary"], 10);
        let b = &v["breakpoints"][0];
        assert!((b["lambda"].as_f64().unwrap() - 1.0).abs() < 1e-12);
        for k in ["yielded", "flow_started", "flow_stopped", "unloaded"] {
            assert!(b[k].is_array(), "{k}");
        }
        assert_eq!(b["flow_started"][0]["node"], "A");
        assert_eq!(b["flow_started"][0]["member"], "AB");
        assert_eq!(b["flow_started"][0]["end"], "from");
        assert_eq!(b["flow_started"][0]["sign"], "negative");
        let order: Vec<&str> = v["hinges"]
            .as_array()
            .unwrap()
            .iter()
            .map(|h| h["node"].as_str().unwrap())
            .collect();
        assert_eq!(order, ["A", "AB.1", "AB.2", "AB.3"]);
        let lambdas: Vec<f64> = v["hinges"]
            .as_array()
            .unwrap()
            .iter()
            .map(|h| h["lambda"].as_f64().unwrap())
            .collect();
        for (l, e) in lambdas.iter().zip([1.0, 4.0, 6.0, 12.0]) {
            assert!((l - e).abs() < 1e-9, "{lambdas:?}");
        }
        let acc = &v["intervals"][1]["accelerations"]["B"]["y"];
        assert_eq!(acc.as_array().unwrap().len(), 2);
        assert!(
            v["moments_at_breakpoints"][0]["members"]["AB"]["from"]
                .as_f64()
                .unwrap()
                + 1.0
                < 1e-9
        );
        let t = v["response"]["times"].as_array().unwrap().len();
        assert_eq!(
            v["response"]["nodes"]["B"]["displacement"]["y"]
                .as_array()
                .unwrap()
                .len(),
            t
        );
    }
}

#[test]
fn export_prints_plcps_json() {
    let out = frames()
        .arg("export")
        .arg(scenes().join("cantilever.toml"))
        .output()
        .unwrap();
    assert!(out.status.success());
    let p = plcp::io::json::parse_plcp::<f64>(&out.stdout, "export").unwrap();
    assert_eq!((p.free(), p.n()), (16, 10));
}

#[test]
fn plots_are_written() {
    let dir = std::env::temp_dir().join(format!("frames-plots-{}", std::process::id()));
    let out = frames()
        .arg("run")
        .arg(scenes().join("cantilever-halftip.toml"))
        .arg("--plots")
        .arg(&dir)
        .output()
        .unwrap();
    assert!(out.status.success());
    for f in ["activation", "profiles", "moments", "displacements"] {
        let svg = std::fs::read_to_string(dir.join(format!("{f}.svg"))).unwrap();
        assert!(svg.starts_with("<svg") && svg.contains("</svg>"), "{f}");
        let csv = std::fs::read_to_string(dir.join(format!("{f}.csv"))).unwrap();
        assert!(csv.lines().count() > 1, "{f}");
    }
}
