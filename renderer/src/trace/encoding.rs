//! rtrace's `-f` letters (how rays are read and values written) and `-o` letters
//! (what each record holds).

/// How rays are read and values written (rtrace's `-f` letters: `-fad` reads text and
/// writes doubles).
#[derive(Clone, Copy, PartialEq, Eq, Debug)]
pub enum RayEncoding {
    Ascii,
    Float,
    Double,
    /// Output only: RGBE pixels (`-fac`, `-ffc`), with `-x -y` a picture.
    Color,
}

impl RayEncoding {
    pub fn from_char(c: char) -> Option<RayEncoding> {
        match c {
            'a' => Some(RayEncoding::Ascii),
            'f' => Some(RayEncoding::Float),
            'd' => Some(RayEncoding::Double),
            'c' => Some(RayEncoding::Color),
            _ => None,
        }
    }

    /// The `-f` letter.
    pub fn letter(self) -> char {
        match self {
            RayEncoding::Ascii => 'a',
            RayEncoding::Float => 'f',
            RayEncoding::Double => 'd',
            RayEncoding::Color => 'c',
        }
    }

    pub fn name(self) -> &'static str {
        match self {
            RayEncoding::Ascii => "ascii",
            RayEncoding::Float => "float",
            RayEncoding::Double => "double",
            RayEncoding::Color => "32-bit_rle_rgbe",
        }
    }
}

/// One `-o` letter.
#[derive(Clone, Copy, PartialEq, Eq, Debug)]
pub enum Output {
    Value,
    Origin,
    Direction,
    Point,
    Normal,
    SurfaceNormal,
    EffectiveLength,
    Length,
    Mirrored,
    MirroredLength,
    Unmirrored,
    UnmirroredLength,
    Surface,
    Modifier,
    Material,
    Tilde,
    Weight,
    LocalCoordinates,
}

impl Output {
    pub fn parse(spec: &str) -> Result<Vec<Output>, String> {
        if spec.is_empty() {
            return Err("empty output specification".into());
        }
        spec.chars()
            .map(|c| {
                Ok(match c {
                    'v' => Output::Value,
                    'o' => Output::Origin,
                    'd' => Output::Direction,
                    'p' => Output::Point,
                    'n' => Output::Normal,
                    'N' => Output::SurfaceNormal,
                    'l' => Output::EffectiveLength,
                    'L' => Output::Length,
                    'r' => Output::Mirrored,
                    'R' => Output::MirroredLength,
                    'x' => Output::Unmirrored,
                    'X' => Output::UnmirroredLength,
                    's' => Output::Surface,
                    'm' => Output::Modifier,
                    'M' => Output::Material,
                    '~' => Output::Tilde,
                    'w' => Output::Weight,
                    'c' => Output::LocalCoordinates,
                    _ => {
                        return Err(format!(
                            "output '{c}' is not supported (radc knows v o d p n N l L r R x X c w s m M ~)"
                        ));
                    }
                })
            })
            .collect()
    }

    pub fn components(self) -> usize {
        match self {
            Output::Value | Output::Origin | Output::Direction | Output::Point | Output::Normal => {
                3
            }
            Output::SurfaceNormal => 3,
            Output::Tilde => 0,
            Output::LocalCoordinates => 2,
            _ => 1,
        }
    }
}
