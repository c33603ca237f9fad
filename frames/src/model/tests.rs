use super::*;

const BASE: &str = r#"
[[node]]
id = "A"
x = 0
y = 0
[[node]]
id = "B"
x = 2.0
y = 0.0
[[member]]
id = "AB"
from = "A"
to = "B"
plastic_moment = 1.0
elements = 4
mass_per_length = 2.0
[[support]]
node = "A"
fix = ["x", "y", "rz"]
[[load]]
node = "B"
fy = -1.0
"#;

fn err(src: &str) -> String {
    Scene::from_toml(src, "s.toml").unwrap_err().to_string()
}

#[test]
fn parses_and_lumps() {
    let s = Scene::from_toml(BASE, "s.toml").unwrap();
    let f = &s.frame;
    assert_eq!(f.nodes.len(), 5);
    assert_eq!(f.nodes[2].id, "AB.1");
    assert_eq!(f.nodes[4].x, 1.5);
    // mu h / 2 to each end: h = 0.5, mu = 2 -> 0.5 per end
    assert_eq!(f.nodes[1].mass, 0.5); // tip: half
    assert_eq!(f.nodes[2].mass, 1.0);
    assert_eq!(f.elements[3].to, 1);
    assert_eq!(s.history, History::Ramp { rate: 1.0 });
}

#[test]
fn errors_name_file_line_key() {
    assert_eq!(
        err(&BASE.replace("to = \"B\"", "to = \"Q\"")),
        "s.toml:13: member \"AB\" to: unknown node \"Q\""
    );
    assert_eq!(
        err(&BASE.replace("id = \"B\"", "id = \"A\"")),
        "s.toml:7: node \"A\" id: duplicate node id \"A\""
    );
    assert_eq!(
        err(&BASE.replace("x = 2.0", "x = 0.0")),
        "s.toml:13: member \"AB\" to: member of zero length (nodes \"A\" and \"B\" coincide)"
    );
    assert_eq!(err(&BASE.replace("mass_per_length = 2.0", "mass_per_length = 0.0")), "s.toml:22: load \"B\" fy: the load acts on a mechanism with no mass on it (node \"B\", component y): add a [[mass]] or mass_per_length, or a support");
    assert_eq!(
        err(&BASE.replace("y = 0.0", "y = nan")),
        "s.toml:9: node \"B\" y: must be a finite number, got NaN"
    );
    let e = err(&BASE.replace("plastic_moment", "plastic_momnet"));
    assert!(
        e.starts_with("s.toml:14:1: plastic_momnet: unknown key \"plastic_momnet\": the accepted keys are `id`, `from`, `to`, `plastic_moment`,"),
        "{e}"
    );
    let e = err(&format!(
        "{BASE}[history]\nkind = \"table\"\npoints = [[0.0, 0.0], [1.0, 2.0], [2.0, 1.0]]\n"
    ));
    assert!(
        e.starts_with("s.toml:25: history points: decreasing history"),
        "{e}"
    );
    assert_eq!(
        err(&BASE.replace("\"rz\"]", "\"rot\"]")),
        "s.toml:19: support \"A\" fix: unknown component \"rot\": expected \"x\", \"y\" or \"rz\""
    );
    assert_eq!(
        err(&BASE.replace("fy = -1.0", "fy = 0.0")),
        "s.toml:0: load: the scene has no nonzero [[load]]: nothing would move"
    );
    let e = err(&BASE.replace("y = 0\n", "y = \n"));
    assert!(e.starts_with("s.toml:5:5: "), "{e}");
    // never more than one line
    assert!(!e.contains('\n'));
}

/// Every table of the contract, each header followed by its keys.
const EVERY_TABLE: [(&str, &str); 11] = [
    ("", "title = \"every table\"\nmodel = \"planar\"\n"),
    ("[yield]", "facets = 8\n"),
    ("[[node]]", "id = \"A\"\nx = 1.0\ny = 0.0\n"),
    ("[[node]]", "id = \"C\"\nx = 0.0\ny = 1.0\n"),
    (
        "[[arc]]",
        "id = \"Q\"\ncentre = [0.0, 0.0]\nradius = 1.0\nstart_angle = 0.0\nend_angle = 90.0\nelements = 4\nfrom = \"A\"\nto = \"C\"\nplastic_moment = 1.0\nplastic_axial = 4.0\nmass_per_length = 1.0\n",
    ),
    (
        "[[member]]",
        "id = \"AB\"\nfrom = \"A\"\nto = \"B\"\nplastic_moment = 1.0\nelements = 2\nmass_per_length = 1.0\n",
    ),
    ("[[support]]", "node = \"A\"\nfix = [\"x\", \"y\", \"rz\"]\n"),
    ("[[mass]]", "node = \"C\"\nm = 1.0\nj = 0.5\n"),
    ("[[load]]", "node = \"C\"\nfy = 1.0\n"),
    ("[history]", "kind = \"ramp\"\nrate = 2.0\n"),
    ("[[target]]", "node = \"C\"\ndirection = [1.0, 0.0, 0.0]\ngap = 0.5\n"),
];

/// The scene with `extra` (a line) right after the header of table `at`.
fn every_table(at: usize, extra: &str) -> String {
    let mut src = String::new();
    for (i, (header, body)) in EVERY_TABLE.iter().enumerate() {
        if !header.is_empty() {
            src.push_str(header);
            src.push('\n');
        }
        if i == at {
            src.push_str(extra);
            src.push('\n');
        }
        src.push_str(body);
        if i == 3 {
            src.push_str("[[node]]\nid = \"B\"\nx = 2.0\ny = 0.0\n");
        }
    }
    src
}

/// Unknown keys were already refused by `deny_unknown_fields`; now the error
/// gives the column, and a `comment` key of any value is accepted in every
/// table (it was an unknown key everywhere).
#[test]
fn every_table_refuses_unknown_keys_and_accepts_comment() {
    let plain = Scene::from_toml(&every_table(usize::MAX, ""), "s.toml").unwrap();
    for (at, (_, body)) in EVERY_TABLE.iter().enumerate() {
        for value in [
            "\"a note\"",
            "3",
            "[1, \"two\"]",
            "{ by = \"me\", rate = 5.0 }",
        ] {
            let src = every_table(at, &format!("comment = {value}"));
            let s = Scene::from_toml(&src, "s.toml")
                .unwrap_or_else(|e| panic!("comment = {value} in table {at}: {e}"));
            assert_eq!(s.frame.nodes.len(), plain.frame.nodes.len());
            assert_eq!(s.history, plain.history);
        }
        let src = every_table(at, "  colour = \"red\"");
        let line = src.lines().position(|l| l.contains("colour")).unwrap() + 1;
        let e = Scene::from_toml(&src, "s.toml").unwrap_err();
        assert!(matches!(e, FramesError::Syntax { .. }), "{e:?}");
        let e = e.to_string();
        let want =
            format!("s.toml:{line}:3: colour: unknown key \"colour\": the accepted keys are ");
        assert!(e.starts_with(&want), "table {at}: {e}");
        assert!(e.contains("`comment`"), "table {at}: {e}");
        // each table lists its own keys
        let own = body.split(" =").next().unwrap();
        assert!(e.contains(&format!("`{own}`")), "table {at}: {e}");
        assert!(!e.contains('\n'));
    }
    // nested and inline tables, and a sub-table of an array-of-tables entry
    let inline = "history = { kind = \"ramp\", rate = 2.0, rat = 3.0 }";
    let src = format!(
        "{inline}\n{}",
        every_table(usize::MAX, "").replace("[history]\nkind = \"ramp\"\nrate = 2.0\n", "")
    );
    assert!(Scene::from_toml(&src.replace(", rat = 3.0", ""), "s.toml").is_ok());
    let e = err(&src);
    let column = inline.find("rat =").unwrap() + 1;
    assert!(
        e.starts_with(&format!("s.toml:1:{column}: rat: unknown key \"rat\""))
            && e.contains("`rate`"),
        "{e}"
    );
    let e = err(&format!(
        "{}[load.extra]\nfz = 1.0\n",
        every_table(usize::MAX, "")
    ));
    assert!(e.contains("extra: unknown key \"extra\""), "{e}");
    let e = err(&format!(
        "{}[units]\nlength = \"m\"\n",
        every_table(usize::MAX, "")
    ));
    assert!(
        e.contains("units: unknown key \"units\"") && e.contains("`node`"),
        "{e}"
    );
}

/// A stray Latin-1 byte (here in a `#` comment) was an I/O error without a
/// position from `read_to_string`; it names offset, line and column.
#[test]
fn invalid_utf8_names_the_position() {
    let src = format!("# r\u{e9}sum\u{e9}\n{BASE}");
    assert!(Scene::from_bytes(src.as_bytes(), "s.toml").is_ok());
    let mut bytes = b"# r\xe9sum\xe9\n".to_vec();
    bytes.extend_from_slice(BASE.as_bytes());
    let e = Scene::from_bytes(&bytes, "s.toml").unwrap_err().to_string();
    assert!(
        e.starts_with("s.toml:1:4: (encoding): invalid UTF-8 at byte offset 3: byte 0xE9"),
        "{e}"
    );
    let mut bytes = BASE.as_bytes().to_vec();
    bytes.extend_from_slice(b"[[mass]]\nnode = \"B\"\nm = 1.0\xff\n");
    let e = Scene::from_bytes(&bytes, "s.toml").unwrap_err().to_string();
    let line = BASE.lines().count() + 3;
    let want = format!(
        "s.toml:{line}:8: (encoding): invalid UTF-8 at byte offset {}",
        BASE.len() + 27
    );
    assert!(e.starts_with(&want), "{e} (want {want})");
}

#[test]
fn histories() {
    let t = History::Table {
        points: vec![(0.0, 0.0), (1.0, 2.0), (3.0, 2.0), (4.0, 3.0)],
    };
    assert_eq!(t.lambda(0.5), 1.0);
    assert_eq!(t.lambda(2.0), 2.0);
    assert_eq!(t.lambda(9.0), 3.0);
    assert_eq!(t.time_at(2.0), Some(1.0));
    assert_eq!(t.time_at(2.5), Some(3.5));
    assert_eq!(t.time_at(3.5), None);
    let s = History::Saturating {
        peak: 2.0,
        tau: 0.5,
    };
    let ts = s.time_at(1.0).unwrap();
    assert!((s.lambda(ts) - 1.0).abs() < 1e-14);
    assert_eq!(s.time_at(2.0), None);
}
