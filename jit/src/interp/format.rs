//! rcalc's output: `printf("%.9g")` per column (`radc_lang::c_number::write_g9`),
//! columns separated by the separator character, a missing column left empty
//! (rcalc.c `chanset`).

use radc_lang::c_number::write_g9;

/// Appends one output line, with its newline (nothing when there are no outputs).
pub fn write_outputs(line: &mut Vec<u8>, values: &[(u32, f64)], sep: char) {
    let mut sep_bytes = [0u8; 4];
    let sep = sep.encode_utf8(&mut sep_bytes).as_bytes();
    let mut col = 0u32;
    for &(n, v) in values {
        if col == 0 {
            col = 1;
        }
        while col < n {
            line.extend_from_slice(sep);
            col += 1;
        }
        write_g9(line, v);
    }
    if col > 0 {
        line.push(b'\n');
    }
}

/// One output line, with its newline; empty when there are no outputs.
pub fn format_outputs(values: &[(u32, f64)], sep: char) -> String {
    let mut line = Vec::new();
    write_outputs(&mut line, values, sep);
    String::from_utf8(line).unwrap_or_default()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn missing_columns_stay_empty() {
        assert_eq!(format_outputs(&[(1, 1.0), (3, 2.0)], '\t'), "1\t\t2\n");
        assert_eq!(format_outputs(&[], '\t'), "");
    }
}
