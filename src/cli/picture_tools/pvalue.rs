//! `radc pvalue`: Radiance's pvalue. Prints a picture's pixels as numbers (`x y r g b`
//! lines in the picture's frame, or data only with `-d`), brightness with `-b`, one
//! primary with `-pr -pg -pb`, undoing the header's exposure with `-o`, in ASCII, `-di`
//! integers, `-db` bytes, `-df` floats or `-dd` doubles; `-r` converts such numbers back
//! to a picture. `-h`/`-H` leave out the header/resolution line (`+h`/`+H` put them
//! back), `-u` prints only values that differ from the one before, `-e` scales by an
//! exposure (`+N`/`-N`: stops), `-R` reverses the channel order, `-x -y` give the
//! resolution of headerless input. Arithmetic is pvalue's: single-precision colours.
use super::{fail, read_input, stdout_position};
use radc_lang::c_number::atof;
use radc_picture::Orientation;
use radc_picture::tools::pvalue::{self, Number, Options, Put};
use radc_picture::tools::{Run, command_line};
use std::process::ExitCode;

const NAME: &str = "pvalue";
/// The options and the index of the first file argument.
fn parse(args: &[String]) -> Result<(Options, usize), String> {
    let mut o = Options {
        header: true,
        resolution: true,
        uniq: false,
        original: false,
        put: Put::All,
        reverse: false,
        number: Number::Ascii,
        format_id: "ascii".into(),
        data_only: false,
        exposure: [1.0; 3],
        do_exposure: false,
        exposure_value: 1.0,
        order: [0, 1, 2],
        orientation: Orientation::STANDARD.0,
        x: 0,
        y: 0,
    };
    let mut i = 0;
    let value = |i: usize| {
        args.get(i + 1)
            .ok_or_else(|| format!("{} needs a value", args[i]))
    };
    while i < args.len() {
        let a = args[i].as_bytes();
        if !matches!(a.first(), Some(b'-' | b'+')) {
            break;
        }
        let minus = a[0] == b'-';
        let unsupported = || format!("option {} is not supported by radc pvalue", args[i]);
        match a.get(1) {
            Some(b'h') => o.header = !minus,
            Some(b'H') => o.resolution = !minus,
            Some(b'u') => o.uniq = minus,
            Some(b'o') => o.original = minus,
            Some(b'r') => o.reverse = minus,
            Some(b'b') => o.put = if minus { Put::Bright } else { Put::All },
            Some(b'R') => o.order = if minus { [2, 1, 0] } else { [0, 1, 2] },
            Some(b'e') => {
                let v = value(i)?;
                let mut d = atof(v);
                if v.starts_with(['-', '+']) {
                    d = 2f64.powf(d);
                }
                if minus {
                    o.exposure_value *= d;
                }
                o.exposure = o.exposure.map(|e| (f64::from(e) * d) as f32);
                o.do_exposure = true;
                i += 1;
            }
            Some(b'p') => match a.get(2) {
                Some(b'r' | b'R') => o.put = Put::Primary(0),
                Some(b'g' | b'G') => o.put = Put::Primary(1),
                Some(b'b' | b'B') => o.put = Put::Primary(2),
                Some(_) | None => return Err(unsupported()),
            },
            Some(b'd') => {
                o.data_only = minus;
                let (number, id) = match a.get(2) {
                    None | Some(b'a') => (Number::Ascii, "ascii"),
                    Some(b'i') => (Number::Int, "ascii"),
                    Some(b'b') => (Number::Byte, "byte"),
                    Some(b'f') => (Number::Float, "float"),
                    Some(b'd') => (Number::Double, "double"),
                    Some(_) => return Err(unsupported()),
                };
                if number != Number::Ascii && number != Number::Int {
                    o.data_only = true;
                }
                o.number = number;
                o.format_id = id.into();
            }
            Some(b'x' | b'X') => {
                o.resolution = false;
                if minus {
                    o.orientation |= Orientation::XDECR;
                } else {
                    o.orientation &= !Orientation::XDECR;
                }
                if o.y == 0 {
                    o.orientation &= !Orientation::YMAJOR;
                }
                o.x = atof(value(i)?) as i64;
                i += 1;
            }
            Some(b'y' | b'Y') => {
                o.resolution = false;
                if minus {
                    o.orientation |= Orientation::YDECR;
                } else {
                    o.orientation &= !Orientation::YDECR;
                }
                if o.x == 0 {
                    o.orientation |= Orientation::YMAJOR;
                }
                o.y = atof(value(i)?) as i64;
                i += 1;
            }
            Some(b's' | b'O' | b'g' | b'n') => return Err(unsupported()),
            _ => return Err(format!("unknown option: {}", args[i])),
        }
        i += 1;
    }
    if o.data_only && o.number == Number::Byte {
        o.format_id = if o.put == Put::All {
            "24-bit_rgb"
        } else {
            "8-bit_grey"
        }
        .into();
    }
    Ok((o, i))
}
pub fn run(args: &[String]) -> ExitCode {
    let (o, files_at) = match parse(args) {
        Ok(o) => o,
        Err(e) => return fail(NAME, e),
    };
    let files = &args[files_at..];
    if files.len() > 1 {
        let why = if o.reverse && files.len() == 3 {
            "three separate channel files are not supported by radc pvalue"
        } else {
            "bad # file arguments"
        };
        return fail(NAME, why);
    }
    let path = files.first().map(String::as_str);
    let data = match read_input(path) {
        Ok(d) => d,
        Err(e) => return fail(NAME, e),
    };
    let what = path.unwrap_or("standard input");
    let run = Run {
        command_line: command_line(&crate::cli::programs::printed_name(NAME), &args[..files_at]),
        output_start: if o.reverse { None } else { stdout_position() },
    };
    let result = if o.reverse {
        pvalue::to_picture(&o, &run, &data, what)
    } else {
        pvalue::to_values(&o, &run, &data, what)
    };
    match result {
        Ok(out) => super::write_output(NAME, None, &out),
        Err(e) => fail(NAME, e),
    }
}
