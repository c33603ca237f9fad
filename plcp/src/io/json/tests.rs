//! Checks of the JSON reader's errors.

use super::*;

fn err(text: &str) -> String {
    parse_plcp::<f64>(text.as_bytes(), "p.json")
        .unwrap_err()
        .to_string()
}

#[test]
fn reads_all_keys() {
    let p = parse_plcp::<f64>(
        br#"{"M": [[1, 0, 0], [0, 2, 1], [0, 1, 2]], "q": [0, 1, "2"], "d": [1, -1, -1],
            "lambda_max": 5.5, "free": 1, "lambda0": -1, "comment": "ignored"}"#,
        "p.json",
    )
    .unwrap();
    assert_eq!((p.dim(), p.n(), p.free()), (3, 2, 1));
    assert_eq!(p.lambda_max(), Some(5.5));
    assert_eq!(p.lambda0(), -1.0);
    assert_eq!(p.m()[(1, 2)], 1.0);
    assert_eq!(p.q()[2], 2.0);
    for lm in ["null", "\"inf\"", "\"Infinity\""] {
        let text = format!(r#"{{"M": [[1]], "q": [1], "d": [1], "lambda_max": {lm}}}"#);
        let p = parse_plcp::<f32>(text.as_bytes(), "p.json").unwrap();
        assert_eq!(p.lambda_max(), None, "{lm}");
    }
}

/// A misspelt key used to be skipped (`lambda_mx`: traced to infinity).
#[test]
fn unknown_keys_are_errors_with_position() {
    let e = err("{\"M\": [[1]], \"q\": [1],\n  \"d\": [1], \"lambda_mx\": 2}");
    assert!(
        e.starts_with("p.json:2:13: unknown key \"lambda_mx\""),
        "{e}"
    );
    for key in [
        "`M`",
        "`q`",
        "`d`",
        "`lambda_max`",
        "`free`",
        "`lambda0`",
        "`comment`",
    ] {
        assert!(e.contains(key), "{key} not listed: {e}");
    }
    // a key with a non-ASCII name, after non-ASCII text on its line: columns count characters
    let e = err("{\"M\": [[1]], \"comment\": \"é\", \"λ\": 1, \"q\": [1], \"d\": [1]}");
    assert!(e.starts_with("p.json:1:30: unknown key \"λ\""), "{e}");
    // `comment` takes any JSON value
    for c in [
        "\"text\"",
        "1",
        "null",
        "[1, \"x\"]",
        "{\"by\": \"me\", \"lambda_max\": 3}",
    ] {
        let text = format!(r#"{{"comment": {c}, "M": [[1]], "q": [1], "d": [1]}}"#);
        let p = parse_plcp::<f64>(text.as_bytes(), "p.json").unwrap();
        assert_eq!(p.lambda_max(), None, "{c}");
    }
}

#[test]
fn invalid_utf8_is_an_error_naming_the_offset() {
    // in an ignored string (serde_json would skip it unchecked), in a key, outside strings
    for (bytes, offset, line, column) in [
        (
            &b"{\"M\": [[1]], \"q\": [1], \"d\": [1], \"comment\": \"\xff\"}"[..],
            45,
            1,
            46,
        ),
        (
            &b"{\"M\": [[1]],\n\"q\": [1], \"d\": [1], \"\xc3\": 1}"[..],
            34,
            2,
            22,
        ),
        (
            &b"{\"M\": [[1]], \"q\": [1], \"d\": [1]}\xe9"[..],
            32,
            1,
            33,
        ),
    ] {
        let e = parse_plcp::<f64>(bytes, "p.json").unwrap_err().to_string();
        let want = format!("p.json:{line}:{column}: invalid UTF-8 at byte offset {offset}:");
        assert!(e.starts_with(&want), "{e} (want {want})");
    }
}

#[test]
fn named_errors() {
    let e = err(r#"{"M": [[1, 2], [3]], "q": [1, 1], "d": [1, 1]}"#);
    assert!(e.contains("M") && e.contains("row 1 with 1 entries"), "{e}");
    let e = err(r#"{"M": [[1, 2, 3], [3, 4, 5]], "q": [1, 1], "d": [1, 1]}"#);
    assert!(e.contains("square") && e.contains("2 x 3"), "{e}");
    let e = err(r#"{"M": [[1, 2], [3, 4]], "q": [1], "d": [1, 1]}"#);
    assert!(e.contains("q has 1 entries"), "{e}");
    let e = err(r#"{"M": [[1, 2], [3, 4]], "q": [1, "NaN"], "d": [1, 1]}"#);
    assert!(e.contains("non-finite entry in q at [1]"), "{e}");
    let e = err(r#"{"M": [[1, 2], [3, 4]], "q": [1, 1], "d": [1, 1], "free": 3}"#);
    assert!(e.contains("free") && e.contains("order 2"), "{e}");
    let e = err("{\"M\": [[1, 2],\n [3, 4]], \"q\": [1, 1], \"d\": [1, 1");
    assert!(e.starts_with("p.json:2:"), "{e}");
    let e = err(r#"{"M": [[1, 2], [3, 4]], "q": [1, 1]}"#);
    assert!(e.contains("missing field `d`"), "{e}");
    let e = err(r#"{"M": [[1, 2], [3, 4]], "q": [1, "x"], "d": [1, 1]}"#);
    assert!(e.contains("p.json:1:") && e.contains("\"x\""), "{e}");
    let e = err(r#"{"M": [[1, 2], [3, 4]], "q": [1, 1], "d": [1, 1], "lambda_max": "NaN"}"#);
    assert!(e.contains("lambda_max"), "{e}");
    let e = err(r#"{"M": [], "q": [], "d": []}"#);
    assert!(e.contains("empty"), "{e}");
    let e = parse_plcp::<f32>(br#"{"M": [[1e300]], "q": [1], "d": [1]}"#, "p.json")
        .unwrap_err()
        .to_string();
    assert!(e.contains("overflows") && e.contains("f32"), "{e}");
}
