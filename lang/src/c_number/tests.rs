use super::*;
use proptest::prelude::*;

#[test]
fn atof_reads_prefixes() {
    assert_eq!(atof("  12.5abc"), 12.5);
    assert_eq!(atof("1.5x"), 1.5);
    assert_eq!(atof("abc"), 0.0);
    assert_eq!(atof("-1e3x"), -1000.0);
    assert_eq!(atof(" -2e3"), -2000.0);
    assert_eq!(atof("1e"), 1.0);
    assert_eq!(atof(".5"), 0.5);
    assert_eq!(atof("0x10"), 16.0);
    assert!(atof("nan").is_nan());
    assert_eq!(atof("-inf"), f64::NEG_INFINITY);
    let huge = strtod(b"1e999");
    assert_eq!((huge.value, huge.out_of_range), (f64::INFINITY, true));
    assert!(strtod(b"1e-999").out_of_range && !strtod(b"0e-999").out_of_range);
}

#[test]
fn strtod_lengths_are_glibcs() {
    for (text, len) in [
        ("  12.5abc", 6),
        ("abc", 0),
        ("-", 0),
        ("+.", 0),
        ("1e", 1),
        ("1e+", 1),
        ("1e+5x", 4),
        ("-Infinity!", 9),
        ("infinit", 3),
        ("NaN", 3),
        ("0x1.8p1z", 7),
        ("0x", 1),
        ("-0xg", 2),
        ("\u{b}\u{c}7", 3),
    ] {
        assert_eq!(strtod(text.as_bytes()).len, len, "{text:?}");
    }
    assert_eq!(atof("0x1.8p1"), 3.0);
}

#[test]
fn atol_saturates_as_strtol() {
    assert_eq!(atol("12abc"), 12);
    assert_eq!(atol(" -7"), -7);
    assert_eq!(atol("x"), 0);
    assert_eq!(atol("99999999999999999999999"), i64::MAX);
    assert_eq!(atol("-99999999999999999999999"), i64::MIN);
    assert_eq!(atoi("-12x"), -12);
    assert_eq!(atoi(b"4294967297".as_slice()), 1);
}

/// The fast path must give strtod's correctly rounded value: std's parser is
/// correctly rounded too, so they must agree on every prefix.
#[test]
fn fast_path_rounds_as_strtod() {
    for text in [
        "0.1",
        "1.7976931348623157e308",
        "9007199254740993",
        "123456789012345678901",
        "0.30000000000000004",
        "1e22",
        "1e23",
        "4.35",
        "-0",
        "-0.0e5",
        "12.5e-3",
    ] {
        assert_eq!(
            atof(text).to_bits(),
            text.parse::<f64>().map_or(0, f64::to_bits),
            "{text}"
        );
    }
}

#[test]
fn number_words_follow_radiance() {
    for ok in [
        "1", "-1.5", "+.5", "5.", "1e3", "1.5E-2", "5.5e3", "1E-2", "1e+2", " 5",
    ] {
        assert!(is_flt(ok), "{ok}");
    }
    for bad in [
        "", ".", "-", "e5", "1e", "1e+", "0x1", "1.5.2", "1,5", "inf", "nan", "1 ", "1e 5",
    ] {
        assert!(!is_flt(bad), "{bad}");
    }
    assert!(is_int("-3") && is_int("007") && !is_int("3.0") && !is_int("+"));
}

#[test]
fn numbers_in_radiance_syntax_only() {
    for (w, v) in [
        ("1", 1.0),
        ("-2.5", -2.5),
        (".5", 0.5),
        ("5.", 5.0),
        ("1e3", 1e3),
        ("+1.5E-2", 0.015),
    ] {
        assert_eq!(real_word(w.as_bytes()), Some(v), "{w}");
    }
    for w in [
        "nan",
        "inf",
        "-infinity",
        "0x10",
        ".",
        "e5",
        "1e",
        "1.2.3",
        "",
        "-",
        "+.",
        "1e+",
        "1.5x",
        "--1",
        "1e5e5",
    ] {
        assert_eq!(real_word(w.as_bytes()), None, "{w}");
    }
}

fn reference_number(w: &str) -> Option<f64> {
    let body = w.strip_prefix(['+', '-']).unwrap_or(w);
    let (mantissa, exponent) = match body.find(['e', 'E']) {
        Some(i) => (&body[..i], Some(&body[i + 1..])),
        None => (body, None),
    };
    let (int, frac) = mantissa.split_once('.').unwrap_or((mantissa, ""));
    let digits = |s: &str| s.bytes().all(|b| b.is_ascii_digit());
    let ok_mantissa = digits(int) && digits(frac) && !(int.is_empty() && frac.is_empty());
    let ok_exponent = exponent.is_none_or(|e| {
        let e = e.strip_prefix(['+', '-']).unwrap_or(e);
        !e.is_empty() && digits(e)
    });
    (ok_mantissa && ok_exponent)
        .then(|| w.parse().ok())
        .flatten()
}

/// The fast parser gives Rust's exactly rounded value, bit for bit (and the sign of
/// zero), on the shapes of number rtrace input has and on long or extreme ones.
#[test]
fn numbers_parse_as_rust_parses_them() {
    let mut words: Vec<String> = [
        "-0",
        "0.0",
        "-0.000",
        "9007199254740993",
        "9007199254740992",
        "123456789012345678901",
        "1e22",
        "1e23",
        "1e-22",
        "1e-23",
        "4.9e-324",
        "1.7976931348623157e308",
        "1e400",
        "-1e-400",
        "0.1",
        "0.30000000000000004",
        "00000000000000000000001.5",
        "1e0000000000000003",
        "1.00000000000000000000001",
        ".000001",
        "2.2250738585072014e-308",
        "1e999999999999",
    ]
    .iter()
    .map(|s| s.to_string())
    .collect();
    let mut seed = 0x2545_f491_4f6c_dd1du64;
    for _ in 0..100_000 {
        seed = seed
            .wrapping_mul(6364136223846793005)
            .wrapping_add(1442695040888963407);
        let x = f64::from_bits(seed >> 2) % 1e6;
        let sign = if seed & 1 == 1 { "-" } else { "" };
        let precision = (seed >> 40) as usize % 12;
        words.push(format!("{sign}{:.precision$}", x.abs()));
        words.push(format!(
            "{sign}{:.precision$e}",
            f64::from_bits(seed & !(1 << 63))
        ));
    }
    for w in &words {
        let fast = real_word(w.as_bytes());
        let reference = reference_number(w);
        assert_eq!(fast.map(f64::to_bits), reference.map(f64::to_bits), "{w}");
    }
}

#[test]
fn real_prefix_stops_where_the_syntax_does() {
    for (w, v, n) in [
        ("1.5x", 1.5, 3),
        ("-2e3.5", -2e3, 4),
        ("7 8", 7.0, 1),
        ("12345678901234567890123 ", 12345678901234567890123.0, 23),
        (".5e-1e", 0.05, 5),
    ] {
        let got = real_prefix(w.as_bytes());
        assert_eq!(
            got.map(|(x, n)| (x.to_bits(), n)),
            Some((f64::to_bits(v), n)),
            "{w}"
        );
    }
    // An exponent marker without digits: no number (no word starting so is one).
    for w in ["x1", "e5", "-x", "+.e1", "", "3e", "3e+ 1"] {
        assert_eq!(real_prefix(w.as_bytes()), None, "{w}");
    }
}

/// The reading the generators had (`strtod_prefix`, words.rs): a decimal after white
/// space, its length, `inf`, `infinity` and `nan`; kept as the reference the shared
/// reader is pinned to on decimal text.
fn decimal_reference(s: &str) -> Option<(f64, usize)> {
    let b = s.as_bytes();
    let mut i = 0;
    while i < b.len() && is_c_space(b[i]) {
        i += 1;
    }
    let start = i;
    if i < b.len() && (b[i] == b'+' || b[i] == b'-') {
        i += 1;
    }
    let rest = &s[i..];
    for word in ["infinity", "inf", "nan"] {
        if rest.len() >= word.len() && rest[..word.len()].eq_ignore_ascii_case(word) {
            let neg = b.get(start) == Some(&b'-');
            let v = if word == "nan" {
                f64::NAN
            } else {
                f64::INFINITY
            };
            return Some((if neg { -v } else { v }, i + word.len()));
        }
    }
    let digits_from = |mut j: usize| {
        while j < b.len() && b[j].is_ascii_digit() {
            j += 1;
        }
        j
    };
    let int_end = digits_from(i);
    let mut end = int_end;
    let mut any = int_end > i;
    if end < b.len() && b[end] == b'.' {
        let frac_end = digits_from(end + 1);
        any |= frac_end > end + 1;
        end = frac_end;
    }
    if !any {
        return None;
    }
    if end < b.len() && (b[end] == b'e' || b[end] == b'E') {
        let mut j = end + 1;
        if j < b.len() && (b[j] == b'+' || b[j] == b'-') {
            j += 1;
        }
        let exp_end = digits_from(j);
        if exp_end > j {
            end = exp_end;
        }
    }
    let value = s[start..end].parse::<f64>().ok()?;
    Some((value, end))
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(5000))]

    #[test]
    fn fast_path_agrees_with_std(m in 0u64..u64::MAX, frac in 0usize..20, e in -40i32..40) {
        let digits = m.to_string();
        let cut = frac.min(digits.len());
        let text = format!("{}.{}e{e}", &digits[..digits.len() - cut], &digits[digits.len() - cut..]);
        let want: f64 = text.parse().unwrap_or(0.0);
        prop_assert_eq!(atof(&text).to_bits(), want.to_bits(), "{}", text);
    }

    /// Text of number characters (no hex): the shared `strtod` reads what the
    /// generators' reader read, value and length.
    #[test]
    fn strtod_equals_the_generators_reader(text in "[ \t+.0-9eEinfatyINF-]{0,24}") {
        let got = strtod(text.as_bytes());
        let want = decimal_reference(&text);
        prop_assert_eq!(
            (got.len > 0).then(|| (got.value.to_bits(), got.len)),
            want.map(|(v, n)| (v.to_bits(), n)),
            "{:?}", text
        );
    }

    /// Radiance's number words read as `strtod` reads them, and are exactly the
    /// words `is_flt` accepts.
    #[test]
    fn real_words_read_as_strtod(text in "[+.0-9eE-]{0,20}") {
        let word = real_word(text.as_bytes());
        prop_assert_eq!(word.is_some(), is_flt(&text));
        prop_assert_eq!(word.is_some(), reference_number(&text).is_some(), "{:?}", text);
        if let Some(v) = word {
            let s = strtod(text.as_bytes());
            prop_assert_eq!((v.to_bits(), text.len()), (s.value.to_bits(), s.len));
        }
    }
}
