//! Radiance's `total` (src/cal/total.c): columns of records reduced to one record: sums
//! (of `|x|^E` with `-sE`), products (`-p`, by logarithms with the sign kept apart),
//! maxima (`-u`), minima (`-l`), means of any of the sums (`-m`), over every `-N`
//! records (`-r`: running totals), from text (blank- or `-tC`-separated), doubles
//! (`-id[N]`) or floats (`-if[N]`), to text (`%.9g`) or binary (`-od`, `-of`).
//! `-in N` and `-on N` stop after N input or output records.

use radc_lang::c_number::{atof, is_c_space, write_g9};

/// The reduction.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Reduce {
    Add,
    Multiply,
    Max,
    Min,
}

impl Reduce {
    /// total.c's `init_val`: also what an empty text field counts as.
    fn initial(self) -> f64 {
        match self {
            Reduce::Add => 0.0,
            Reduce::Multiply => 1.0,
            Reduce::Max => -1e12,
            Reduce::Min => 1e12,
        }
    }
}

/// How numbers are read or written: text, or native doubles or floats (with the count
/// of columns a binary input record holds).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Numbers {
    Text,
    Double(usize),
    Float(usize),
}

/// total's settings, as its options leave them.
#[derive(Clone, Debug)]
pub struct TotalOptions {
    pub reduce: Reduce,
    pub power: f64,
    pub mean: bool,
    /// `-N`: records per result (0: all).
    pub count: usize,
    pub running: bool,
    pub separator: u8,
    pub input: Numbers,
    pub output: Numbers,
    pub in_limit: usize,
    pub out_limit: usize,
}

impl Default for TotalOptions {
    fn default() -> TotalOptions {
        TotalOptions {
            reduce: Reduce::Add,
            power: 0.0,
            mean: false,
            count: 0,
            running: false,
            separator: b'\t',
            input: Numbers::Text,
            output: Numbers::Text,
            in_limit: 0,
            out_limit: 0,
        }
    }
}

/// The most columns a record may have (total.c's `MAXCOL`).
pub const MAX_COLUMNS: usize = 81920;

/// Reads records from one input.
struct Reader<'a> {
    data: &'a [u8],
    pos: usize,
}

impl Reader<'_> {
    fn record(&mut self, o: &TotalOptions, fields: &mut Vec<f64>) -> usize {
        fields.clear();
        let binary = |size: usize, n: usize, r: &mut Self, fields: &mut Vec<f64>| {
            for _ in 0..n {
                let Some(b) = r.data.get(r.pos..r.pos + size) else {
                    break;
                };
                r.pos += size;
                fields.push(if size == 8 {
                    f64::from_ne_bytes(b.try_into().unwrap_or([0; 8]))
                } else {
                    f64::from(f32::from_ne_bytes(b.try_into().unwrap_or([0; 4])))
                });
            }
            fields.len()
        };
        match o.input {
            Numbers::Double(n) => return binary(8, n, self, fields),
            Numbers::Float(n) => return binary(4, n, self, fields),
            Numbers::Text => {}
        }
        if self.pos >= self.data.len() {
            return 0;
        }
        let rest = &self.data[self.pos..];
        let end = rest
            .iter()
            .position(|&c| c == b'\n')
            .map_or(rest.len(), |n| n + 1);
        let line = &rest[..end];
        self.pos += end;
        let sep_is_space = is_c_space(o.separator);
        let mut i = 0;
        while fields.len() < MAX_COLUMNS {
            while i < line.len() && is_c_space(line[i]) {
                i += 1;
            }
            if i >= line.len() {
                break;
            }
            let start = i;
            while i < line.len()
                && !(if sep_is_space {
                    is_c_space(line[i])
                } else {
                    line[i] == o.separator
                })
            {
                i += 1;
            }
            let word = &line[start..i];
            if i < line.len() {
                i += 1;
            }
            fields.push(if word.is_empty() || is_c_space(word[0]) {
                o.reduce.initial()
            } else {
                atof(&String::from_utf8_lossy(word))
            });
        }
        fields.len()
    }
}

/// Runs total over one input's bytes (total.c `execute`), appending results to `out`;
/// `records_out` counts results over all inputs, for `-on`.
pub fn total(o: &TotalOptions, data: &[u8], out: &mut Vec<u8>, records_out: &mut usize) {
    let mut tally = Vec::new();
    let mut sign = Vec::new();
    let mut fields = Vec::new();
    {
        if o.out_limit > 0 && *records_out >= o.out_limit {
            return;
        }
        let mut reader = Reader { data, pos: 0 };
        let mut lines_total = 0usize;
        loop {
            if lines_total == 0 {
                tally.clear();
                sign.clear();
            }
            let mut columns = 0;
            let mut lines = 0usize;
            while (o.count == 0 || lines < o.count) && (o.in_limit == 0 || lines < o.in_limit) {
                let n = reader.record(o, &mut fields);
                if n == 0 {
                    break;
                }
                if tally.len() < n {
                    let init = if o.reduce == Reduce::Multiply {
                        0.0
                    } else {
                        o.reduce.initial()
                    };
                    tally.resize(n, init);
                    sign.resize(n, 1);
                }
                for (k, &v) in fields.iter().enumerate() {
                    match o.reduce {
                        Reduce::Add => {
                            if v == 0.0 {
                                continue;
                            }
                            tally[k] += if o.power == 0.0 {
                                v
                            } else if o.power == 1.0 {
                                v.abs()
                            } else if o.power == -1.0 {
                                1.0 / v.abs()
                            } else {
                                v.abs().powf(o.power)
                            };
                        }
                        Reduce::Multiply => {
                            let mut v = v;
                            if v == 0.0 {
                                sign[k] = 0;
                            } else if v < 0.0 {
                                sign[k] = -sign[k];
                                v = -v;
                            }
                            if sign[k] != 0 {
                                tally[k] += v.ln();
                            }
                        }
                        Reduce::Max => {
                            if v > tally[k] {
                                tally[k] = v;
                            }
                        }
                        Reduce::Min => {
                            if v < tally[k] {
                                tally[k] = v;
                            }
                        }
                    }
                }
                columns = columns.max(n);
                lines += 1;
            }
            if lines == 0 {
                break;
            }
            lines_total += lines;
            let result: Vec<f64> = (0..columns)
                .map(|k| {
                    let mut r = tally[k];
                    if o.mean {
                        r /= lines_total as f64;
                        if o.reduce == Reduce::Add && o.power != 0.0 && r != 0.0 {
                            r = r.powf(1.0 / o.power);
                        }
                    }
                    if o.reduce == Reduce::Multiply {
                        r = f64::from(sign[k]) * r.exp();
                    }
                    r
                })
                .collect();
            put(o, &result, out);
            *records_out += 1;
            if o.out_limit > 0 && *records_out >= o.out_limit {
                break;
            }
            if !o.running {
                lines_total = 0;
            }
            if o.in_limit > 0 && lines >= o.in_limit {
                break;
            }
        }
    }
}

fn put(o: &TotalOptions, result: &[f64], out: &mut Vec<u8>) {
    match o.output {
        Numbers::Double(_) => result
            .iter()
            .for_each(|v| out.extend_from_slice(&v.to_ne_bytes())),
        Numbers::Float(_) => result
            .iter()
            .for_each(|v| out.extend_from_slice(&(*v as f32).to_ne_bytes())),
        Numbers::Text => {
            for (i, &v) in result.iter().enumerate() {
                write_g9(out, v);
                if i + 1 < result.len() {
                    out.push(o.separator);
                }
            }
            out.push(b'\n');
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn run(o: &TotalOptions, text: &str) -> String {
        let mut out = Vec::new();
        total(o, text.as_bytes(), &mut out, &mut 0);
        String::from_utf8_lossy(&out).into_owned()
    }

    #[test]
    fn sums_means_products_and_extremes() {
        let data = "1 2 3\n4 5 6\n-2 1\n";
        assert_eq!(run(&TotalOptions::default(), data), "3\t8\t9\n");
        let mean = TotalOptions {
            mean: true,
            ..TotalOptions::default()
        };
        assert_eq!(run(&mean, data), "1\t2.66666667\t3\n");
        let product = TotalOptions {
            reduce: Reduce::Multiply,
            ..TotalOptions::default()
        };
        assert_eq!(run(&product, data), "-8\t10\t18\n");
        let max = TotalOptions {
            reduce: Reduce::Max,
            ..TotalOptions::default()
        };
        assert_eq!(run(&max, data), "4\t5\t6\n");
    }

    #[test]
    fn counts_and_running_totals() {
        let data = "1\n2\n3\n4\n5\n";
        let every2 = TotalOptions {
            count: 2,
            ..TotalOptions::default()
        };
        assert_eq!(run(&every2, data), "3\n7\n5\n");
        let running = TotalOptions {
            count: 2,
            running: true,
            ..TotalOptions::default()
        };
        assert_eq!(run(&running, data), "3\n10\n15\n");
    }

    proptest::proptest! {
        /// Any bytes, as text or binary records, give results and no panic.
        #[test]
        fn any_input_is_reduced(
            data in proptest::collection::vec(proptest::prelude::any::<u8>(), 0..400),
            kind in 0usize..3,
            count in 0usize..4,
        ) {
            let o = TotalOptions {
                input: [Numbers::Text, Numbers::Double(2), Numbers::Float(3)][kind],
                count,
                running: count % 2 == 1,
                reduce: [Reduce::Add, Reduce::Multiply, Reduce::Max][kind],
                ..TotalOptions::default()
            };
            let mut out = Vec::new();
            total(&o, &data, &mut out, &mut 0);
        }
    }
}
