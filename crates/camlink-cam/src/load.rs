//! Reading a design file into a [`Design`]: every key typed and bounded,
//! the motion program and the follower's geometry checked by synthesising
//! the cam, the sizing tables (`[contact]`, `[spring]`, `[vibration]`)
//! read against it, and the export settings held to the profile's size.

use std::f64::consts::TAU;
use std::path::Path;

use camlink_core::cam::hertz::{self, Material};
use camlink_core::cam::spring::Helical;
use camlink_core::cam::{self, Cam, Follower, LawKind, MotionError, Program};
use camlink_core::fmt_num::num;
use camlink_model::LoadError;
use toml::{Table as Map, Value};

use crate::design::*;
use crate::limits::*;
use crate::table::{fail, Fail, Num, Table, R};

/// A checked design file and what the loader has to say about it (each
/// warning names the file and the field).
#[derive(Clone, Debug)]
pub struct Loaded {
    pub design: Design,
    pub warnings: Vec<String>,
}

/// Reads and checks the design file at `path` (TOML).
pub fn load_path(path: &Path) -> Result<Loaded, LoadError> {
    let text = camlink_model::text::read_text(path)?;
    load_toml(&text, &path.display().to_string())
}

/// Checks the design file `text` (TOML); `source` names it in messages,
/// and its stem names the default exports. Errors give the line and
/// column of the field.
pub fn load_toml(text: &str, source: &str) -> Result<Loaded, LoadError> {
    let text = text.strip_prefix('\u{feff}').unwrap_or(text);
    let doc = parse_toml(text, source)?;
    read(&doc, source).map_err(|f| located(f, Some(text), source))
}

/// The TOML table `text` (without a byte order mark); a syntax error gives
/// its line and column.
pub(crate) fn parse_toml(text: &str, source: &str) -> Result<Map, LoadError> {
    text.parse().map_err(|e: toml::de::Error| {
        let (line, column) = e
            .span()
            .map(|s| camlink_model::text::line_col(text, s.start))
            .unzip();
        LoadError {
            source: source.to_string(),
            line,
            column,
            field: None,
            message: format!("syntax error: {}", e.message().trim()),
        }
    })
}

/// Checks a design file given as JSON `text` (the data of a TOML file, as
/// an editor holds it); errors name the field but no line.
pub fn load_json(text: &str, source: &str) -> Result<Loaded, LoadError> {
    let doc = json_table(text).map_err(|message| LoadError {
        source: source.to_string(),
        line: None,
        column: None,
        field: None,
        message,
    })?;
    read(&doc, source).map_err(|f| located(f, None, source))
}

/// Whether `doc` is a cam design file (a motion program: top-level
/// `[[segments]]` and `[follower]`) rather than a model file.
pub fn is_design(doc: &Map) -> bool {
    matches!(doc.get("segments"), Some(Value::Array(_)))
        && doc.contains_key("follower")
        && !doc.contains_key("bodies")
}

/// The JSON object `text` as a TOML table.
pub fn json_table(text: &str) -> Result<Map, String> {
    let v: serde_json::Value =
        serde_json::from_str(text).map_err(|e| format!("syntax error: {e}"))?;
    match Value::try_from(v) {
        Ok(Value::Table(t)) => Ok(t),
        Ok(_) => Err("a design file is a table".into()),
        Err(e) => Err(e.to_string()),
    }
}

/// The load error of `f`, at its field's line in TOML `text`.
pub(crate) fn located(f: Fail, text: Option<&str>, source: &str) -> LoadError {
    let (line, column) = text
        .zip(f.field.as_deref())
        .and_then(|(t, p)| camlink_model::toml_position(t, p))
        .unzip();
    LoadError {
        source: source.to_string(),
        line,
        column,
        field: f.field,
        message: f.message,
    }
}

/// The stem and the file name of the path `source` (empty when it has none).
pub(crate) fn stem_and_name(source: &str) -> (String, String) {
    let path = Path::new(source);
    let text =
        |s: Option<&std::ffi::OsStr>| s.map_or(String::new(), |s| s.to_string_lossy().into_owned());
    (text(path.file_stem()), text(path.file_name()))
}

fn read(doc: &Map, source: &str) -> R<Loaded> {
    let (stem, file_name) = stem_and_name(source);
    let mut warnings = Vec::new();
    let mut top = Table::root(doc);
    let name = top.text("name", Some(&stem), &[])?;

    // [cam]
    let mut c = top.table("cam")?;
    let base_radius = c.number("base_radius", None, Num::POSITIVE_LENGTH)?;
    if let Some(q) = cam::base_radius_question(base_radius) {
        warnings.push(format!(
            "{source}: [cam] base_radius: {q} (design files are in metres)"
        ));
    }
    let ccw = c.choice("rotation", Some("ccw"), &[("ccw", true), ("cw", false)])?;
    c.finish()?;

    // [follower]: its dimensions as the core's table lists them.
    let mut f = top.table("follower")?;
    let kinds: Vec<&str> = Follower::KINDS.iter().map(|(k, _)| *k).collect();
    let kind = f.text("type", None, &kinds)?;
    let read = Follower::read(&kind, |key, zero_default| match zero_default {
        true => f.number(key, Some(0.0), Num::LENGTH),
        false => f.number(key, None, Num::POSITIVE_LENGTH),
    });
    let Some(read) = read else {
        return f.fail("type", format!("'{kind}' is not a follower"));
    };
    let (shape, dims) = read?;
    let follower = shape.name();
    f.finish()?;
    let oscillating = follower.starts_with("oscillating");

    // [[segments]]
    top.mark("segments");
    let raw = match top.get("segments") {
        Some(Value::Array(a)) if !a.is_empty() => a,
        _ => {
            return fail(
                "segments",
                "the motion program needs at least one segment ([[segments]])",
            )
        }
    };
    if raw.len() > MAX_SEGMENTS {
        return fail(
            "segments",
            format!(
                "{} [[segments]]; a motion program has at most {MAX_SEGMENTS}",
                raw.len()
            ),
        );
    }
    let laws: Vec<(&str, LawKind)> = LawKind::ALL.iter().map(|&l| (l.name(), l)).collect();
    let mut segments = Vec::with_capacity(raw.len());
    for (i, r) in raw.iter().enumerate() {
        let mut s = Table::new(format!("segments[{i}]"), Some(r))?;
        let law = s.choice("law", None, &laws)?;
        let span_deg = s.number("span_deg", None, Num::POSITIVE.most(360.0, "°"))?;
        if span_deg < MIN_SPAN_DEG {
            return s.fail(
                "span_deg",
                format!(
                    "must be at least {}°, got {}",
                    num(MIN_SPAN_DEG),
                    num(span_deg)
                ),
            );
        }
        let lift = if oscillating {
            s.number("swing_deg", Some(0.0), Num::ANY.most(180.0, "°"))?
                .to_radians()
        } else {
            s.number("lift", Some(0.0), Num::LENGTH)?
        };
        let start = ends(&mut s, "start")?;
        let end = ends(&mut s, "end")?;
        s.finish()?;
        segments.push(Segment {
            law,
            span: span_deg.to_radians(),
            lift,
            start,
            end,
        });
    }

    let limits = read_limits(&mut top)?;

    // [dynamics]
    let mut dynamics = None;
    let mut dynamics_given: Vec<String> = Vec::new();
    if top.has("dynamics") {
        let mut d = top.table("dynamics")?;
        let redline = d.optional("redline_rpm", Num::POSITIVE.most(MAX_RPM, " rpm"))?;
        let dy = Dynamics {
            mass: d.number("mass", None, Num::POSITIVE)?,
            spring_rate: d.number("spring_rate", Some(0.0), Num::ANY)?,
            preload: d.number("preload", Some(0.0), Num::ANY)?,
            damping: d.number("damping", Some(0.0), Num::ANY)?,
            speed: d.number("speed_rpm", None, Num::POSITIVE.most(MAX_RPM, " rpm"))? * RPM,
            redline: redline.map(|r| r * RPM),
        };
        for (key, v) in [
            ("spring_rate", dy.spring_rate),
            ("preload", dy.preload),
            ("damping", dy.damping),
        ] {
            if v < 0.0 {
                return d.fail(key, "must not be negative");
            }
        }
        dynamics_given = d.keys().cloned().collect();
        d.finish()?;
        dynamics = Some(dy);
    }
    let sizing: Vec<&str> = ["contact", "spring", "vibration"]
        .into_iter()
        .filter(|k| top.has(k))
        .collect();
    for k in &sizing {
        top.mark(k);
    }

    let export = read_export(&mut top, &stem, &file_name, dynamics.is_some())?;
    top.finish()?;

    let mut design = Design {
        source: source.to_string(),
        name,
        follower,
        dims,
        base_radius,
        ccw,
        segments,
        limits,
        dynamics,
        export,
        contact: None,
        spring: None,
        vibration: None,
    };
    // The program and the follower's geometry, checked by synthesis.
    let cam = design.cam().map_err(|e| match e {
        CamBuildError::Program(MotionError::Segment { segment, message }) => Fail {
            field: Some(format!("segments[{segment}]")),
            message,
        },
        CamBuildError::Program(e @ MotionError::NotClosed(_)) => Fail {
            field: Some("segments".into()),
            message: e.to_string(),
        },
        CamBuildError::Follower(message) => Fail {
            field: Some("follower".into()),
            message,
        },
        CamBuildError::Geometry(e) => Fail {
            field: None,
            message: e.to_string(),
        },
    })?;
    read_sizing(doc, &sizing, &dynamics_given, &cam.program, &mut design)?;
    check_profile(&cam, &design.export)?;
    Ok(Loaded { design, warnings })
}

/// A segment's `start` or `end`: s′, s″, s‴ of a fitted polynomial
/// (per rad of cam angle), `None` where not given.
fn ends(t: &mut Table, key: &str) -> R<[Option<f64>; 3]> {
    let mut out = [None; 3];
    let mut e = t.table(key)?;
    for (k, name) in ["velocity", "acceleration", "jerk"].into_iter().enumerate() {
        out[k] = e.optional(name, Num::ANY)?;
    }
    e.finish()?;
    Ok(out)
}

/// `[limits]`.
fn read_limits(top: &mut Table) -> R<Limits> {
    let mut lim = top.table("limits")?;
    let phi = lim.optional("max_pressure_angle_deg", Num::POSITIVE.most(90.0, "°"))?;
    lim.mark("base_radius_search");
    let range = match lim.get("base_radius_search") {
        None => None,
        Some(v) => {
            let pair = match v {
                Value::Array(a) if a.len() == 2 => number(&a[0]).zip(number(&a[1])),
                _ => None,
            };
            match pair {
                Some((lo, hi)) if 0.0 < lo && lo < hi && hi <= MAX_LENGTH => Some((lo, hi)),
                _ => {
                    return lim.fail(
                        "base_radius_search",
                        format!(
                            "must be [lo, hi] with 0 < lo < hi ≤ {} (m), got {}",
                            num(MAX_LENGTH),
                            crate::table::repr(v)
                        ),
                    )
                }
            }
        }
    };
    let limits = Limits {
        max_pressure_angle: phi.map(f64::to_radians),
        min_radius: lim.optional("min_radius", Num::POSITIVE_LENGTH)?,
        max_face_width: lim.optional("max_face_width", Num::POSITIVE_LENGTH)?,
        base_radius_range: range,
        max_contact_stress: lim.optional("max_contact_stress", Num::POSITIVE)?,
        min_bearing_life_hours: lim.optional("min_bearing_life_hours", Num::POSITIVE)?,
        min_coil_clearance: lim.optional("min_coil_clearance", Num::POSITIVE_LENGTH)?,
        min_surge_ratio: lim.number("min_surge_ratio", Some(SURGE_RATIO), Num::POSITIVE)?,
        max_residual_vibration: lim.optional("max_residual_vibration", Num::POSITIVE)?,
    };
    lim.finish()?;
    Ok(limits)
}

/// A plain number (an integer or a float, not a flag).
fn number(v: &Value) -> Option<f64> {
    match v {
        Value::Integer(i) => Some(*i as f64),
        Value::Float(f) => Some(*f),
        _ => None,
    }
}

/// `[export]`; `stem` names the default files, `file_name` is the design
/// file's own name.
fn read_export(top: &mut Table, stem: &str, file_name: &str, dynamics: bool) -> R<Export> {
    let vibration = top.has("vibration");
    let mut ex = top.table("export")?;
    let mut names: Vec<(String, &str)> = Vec::new();
    let mut given: Vec<String> = Vec::new();
    let mut out = |ex: &mut Table, key: &'static str, default: String| -> R<Option<String>> {
        ex.mark(key);
        let v = match ex.get(key) {
            None => default,
            Some(Value::Boolean(false)) => return Ok(None),
            Some(Value::String(s)) if !s.is_empty() => s.clone(),
            Some(other) => {
                return ex.fail(
                    key,
                    format!(
                        "must be a file name or false, got {}",
                        crate::table::repr(other)
                    ),
                )
            }
        };
        if let Some(problem) = not_plain(&v) {
            return ex.fail(
                key,
                format!("'{v}' {problem}; an export is a plain file name inside the output folder"),
            );
        }
        if v == file_name {
            return ex.fail(
                key,
                format!("'{v}' is the design file's name; choose another file name"),
            );
        }
        if let Some((_, other)) = names.iter().find(|(n, _)| *n == v) {
            return ex.fail(
                key,
                format!("'{v}' is also export.{other}; each export needs its own file"),
            );
        }
        names.push((v.clone(), key));
        if ex.has(key) {
            given.push(key.to_string());
        }
        Ok(Some(v))
    };
    let csv_chord = ex.optional("csv_chord_tolerance", Num::POSITIVE_LENGTH)?;
    let csv_step = match csv_chord {
        Some(_) => 0.0,
        None => {
            let step = ex.number("csv_step_deg", Some(CSV_STEP_DEG), Num::POSITIVE)?;
            let rows = 360.0 / step;
            if rows > MAX_CSV_ROWS as f64 {
                return ex.fail(
                    "csv_step_deg",
                    format!(
                        "{}° makes {} rows; the CSV holds at most {MAX_CSV_ROWS} (a step of at \
                         least {}°)",
                        num(step),
                        num(rows),
                        num(360.0 / MAX_CSV_ROWS as f64)
                    ),
                );
            }
            step.to_radians()
        }
    };
    let csv = out(&mut ex, "csv", format!("{stem}.csv"))?;
    let dxf = out(&mut ex, "dxf", format!("{stem}.dxf"))?;
    let dxf_mode = ex.choice(
        "dxf_mode",
        Some("polyline"),
        &[("polyline", DxfMode::Polyline), ("arcs", DxfMode::Arcs)],
    )?;
    let tolerance = ex.number("tolerance", Some(TOLERANCE), Num::POSITIVE_LENGTH)?;
    let svg = out(&mut ex, "svg", format!("{stem}.svg"))?;
    let tool_radius = ex.optional("tool_radius", Num::POSITIVE_LENGTH)?;
    let svaj = out(&mut ex, "svaj_plot", format!("{stem}_svaj.png"))?;
    let profile = out(&mut ex, "profile_plot", format!("{stem}_profile.png"))?;
    let units = ex.text("units", Some("m"), &["m", "mm"])?;
    let svaj_time = match dynamics {
        true => out(&mut ex, "svaj_time_plot", format!("{stem}_svaj_time.png"))?,
        false => None,
    };
    let vibration = match vibration {
        true => out(&mut ex, "vibration_plot", format!("{stem}_vibration.png"))?,
        false => None,
    };
    let bore = ex.optional("bore_diameter", Num::POSITIVE_LENGTH)?;
    let kw = ex.optional("keyway_width", Num::POSITIVE_LENGTH)?;
    let kd = ex.optional("keyway_depth", Num::POSITIVE_LENGTH)?;
    let ka = ex.number("keyway_angle_deg", Some(0.0), Num::ANY.most(360.0, "°"))?;
    let timing_mark = ex.flag("timing_mark", true)?;
    for (key, v) in [("keyway_width", kw), ("keyway_depth", kd)] {
        if v.is_some() && bore.is_none() {
            return ex.fail(key, "needs export.bore_diameter");
        }
    }
    if kw.is_none() != kd.is_none() {
        let key = if kw.is_none() {
            "keyway_width"
        } else {
            "keyway_depth"
        };
        return ex.fail(key, "a keyway needs both width and depth");
    }
    if let (Some(b), Some(w)) = (bore, kw) {
        if w >= b {
            return ex.fail(
                "keyway_width",
                format!("{} m must be narrower than the bore {} m", num(w), num(b)),
            );
        }
    }
    ex.finish()?;
    Ok(Export {
        csv,
        csv_step,
        csv_chord,
        dxf,
        dxf_mode,
        tolerance,
        svg,
        tool_radius,
        svaj,
        profile,
        given,
        units,
        svaj_time,
        vibration,
        bore_radius: bore.map(|b| b / 2.0),
        keyway_width: kw,
        keyway_depth: kd,
        keyway_angle: ka.to_radians(),
        timing_mark,
    })
}

/// Why `name` is not a plain file name (an export's or a file named
/// beside the design); `None` when it is.
pub fn not_plain(name: &str) -> Option<&'static str> {
    let b = name.as_bytes();
    if name.contains(['/', '\\']) {
        Some("holds a path separator")
    } else if name == "." || name == ".." {
        Some("is a folder")
    } else if name.chars().any(|c| (c as u32) < 32) {
        Some("holds a control character")
    } else if b.len() >= 2 && b[0].is_ascii_alphabetic() && b[1] == b':' {
        Some("is an absolute path")
    } else {
        None
    }
}

/// A material of `[contact]` or `[spring]` at `key` (default steel): a
/// name from the core's table, or `{ young_modulus, poisson_ratio[,
/// shear_modulus, density] }` (Pa, kg/m³), named "given".
fn material(t: &mut Table, key: &str) -> R<(String, Material)> {
    t.mark(key);
    match t.get(key) {
        None => Ok(("steel".into(), hertz::material("steel").expect("steel"))),
        Some(Value::String(name)) => match hertz::material(name) {
            Some(m) => Ok((name.clone(), m)),
            None => t.fail(
                key,
                format!(
                    "'{name}' is not in the materials table ({}); give \
                     {{ young_modulus = …, poisson_ratio = … }} (Pa) instead",
                    hertz::material_names()
                ),
            ),
        },
        Some(v) => {
            let mut m = Table::new(t.field(key), Some(v))?;
            let young = m.number("young_modulus", None, Num::POSITIVE)?;
            let poisson = m.number("poisson_ratio", None, Num::ANY)?;
            if !(0.0..0.5).contains(&poisson) {
                return m.fail(
                    "poisson_ratio",
                    format!("must be in [0, 0.5), got {}", num(poisson)),
                );
            }
            let shear = m.optional("shear_modulus", Num::POSITIVE)?;
            let density = m.optional("density", Num::POSITIVE)?;
            m.finish()?;
            Ok((
                "given".into(),
                Material {
                    young,
                    poisson,
                    shear: shear.unwrap_or(f64::NAN),
                    density: density.unwrap_or(f64::NAN),
                },
            ))
        }
    }
}

/// `[contact]`, `[spring]` and `[vibration]` (the keys of `sizing` that
/// the file gives) into `design`; the spring sets the rate and preload of
/// `[dynamics]`, whose keys the file gives are `dynamics_given`.
fn read_sizing(
    doc: &Map,
    sizing: &[&str],
    dynamics_given: &[String],
    program: &Program,
    design: &mut Design,
) -> R<()> {
    let Some(dynamics) = design.dynamics.as_mut() else {
        return match sizing.first() {
            Some(key) => fail(
                *key,
                format!("[{key}] needs [dynamics] (the follower's mass and speed)"),
            ),
            None => Ok(()),
        };
    };
    let flat = design.follower.ends_with("flat");
    if doc.contains_key("contact") {
        let mut t = Table::new("contact", doc.get("contact"))?;
        let width = t.number("width", None, Num::POSITIVE_LENGTH)?;
        let (cam_name, cam_m) = material(&mut t, "cam_material")?;
        let (fol_name, fol_m) = material(&mut t, "follower_material")?;
        let rating = t.optional("bearing_rating", Num::POSITIVE)?;
        let exponent = t.choice("bearing_type", Some("ball"), &LIFE_EXPONENTS)?;
        if rating.is_some() && flat {
            return t.fail(
                "bearing_rating",
                "a flat-faced follower has no roller bearing",
            );
        }
        let crown = t.optional("crown_radius", Num::POSITIVE_LENGTH)?;
        if crown.is_some() && flat {
            return t.fail(
                "crown_radius",
                "a flat-faced follower has no roller to crown",
            );
        }
        t.finish()?;
        design.contact = Some(ContactSpec {
            width,
            modulus: hertz::contact_modulus(&cam_m, &fol_m),
            materials: (cam_name, fol_name),
            rating,
            exponent,
            crown,
        });
    }
    if doc.contains_key("spring") {
        let mut t = Table::new("spring", doc.get("spring"))?;
        if design.follower.starts_with("oscillating") {
            return fail(
                "spring",
                "a helical spring on the stem needs a translating follower; give \
                 dynamics.spring_rate and preload (per radian) for an oscillating one",
            );
        }
        for key in ["spring_rate", "preload"] {
            if dynamics_given.iter().any(|k| k == key) {
                return fail(
                    format!("dynamics.{key}"),
                    "[spring] gives the rate and preload; remove one of them",
                );
            }
        }
        let wire = t.number("wire_diameter", None, Num::POSITIVE_LENGTH)?;
        let mean_diameter = t.number("mean_diameter", None, Num::POSITIVE_LENGTH)?;
        let free_length = t.number("free_length", None, Num::POSITIVE_LENGTH)?;
        let installed_length = t.number("installed_length", None, Num::POSITIVE_LENGTH)?;
        let coils = Num::POSITIVE.most(MAX_COILS, "");
        let active_coils = t.number("active_coils", None, coils)?;
        let total_coils = t.number("total_coils", None, coils)?;
        let (shear_modulus, density) = if t.has("shear_modulus") || t.has("density") {
            (
                t.number("shear_modulus", None, Num::POSITIVE)?,
                t.number("density", None, Num::POSITIVE)?,
            )
        } else {
            let (_, m) = material(&mut t, "material")?;
            if !(m.shear.is_finite() && m.density.is_finite()) {
                return t.fail("material", "needs shear_modulus and density for a spring");
            }
            (m.shear, m.density)
        };
        t.finish()?;
        let spring = Helical {
            wire,
            mean_diameter,
            active_coils,
            total_coils,
            free_length,
            shear_modulus,
            density,
        };
        let figures = spring
            .install(installed_length, largest_lift(program))
            .map_err(|e| Fail {
                field: Some(format!("spring.{}", e.field)),
                message: e.message,
            })?;
        dynamics.spring_rate = figures.rate;
        dynamics.preload = figures.preload;
        design.spring = Some(SpringSpec {
            wire,
            mean_diameter,
            active_coils,
            total_coils,
            free_length,
            installed_length,
            shear_modulus,
            density,
            figures,
        });
    }
    if doc.contains_key("vibration") {
        let mut t = Table::new("vibration", doc.get("vibration"))?;
        let masses = numbers(&mut t, "masses", Some(vec![dynamics.mass]), true)?;
        let stiffness = numbers(&mut t, "stiffness", None, true)?;
        let damping = numbers(&mut t, "damping", Some(vec![0.0; masses.len()]), false)?;
        for (key, v) in [("stiffness", &stiffness), ("damping", &damping)] {
            if v.len() != masses.len() {
                return t.fail(
                    key,
                    format!(
                        "gives {} values for {} masses; one per mass",
                        v.len(),
                        masses.len()
                    ),
                );
            }
        }
        let steps = t.number(
            "steps_per_turn",
            Some(7200.0),
            Num::POSITIVE.most(MAX_STEPS as f64, ""),
        )?;
        let turns = t.number("turns", Some(3.0), Num::POSITIVE.most(MAX_TURNS as f64, ""))?;
        for (key, v) in [("steps_per_turn", steps), ("turns", turns)] {
            if v.fract() != 0.0 {
                return t.fail(key, format!("is {}: a whole number is needed", num(v)));
            }
        }
        let (steps, turns) = (steps as usize, turns as usize);
        let polydyne = t.flag("polydyne", false)?;
        if polydyne && masses.len() != 1 {
            return t.fail(
                "polydyne",
                format!("takes a one-mass train, got {} masses", masses.len()),
            );
        }
        t.finish()?;
        design.vibration = Some(VibrationSpec {
            masses,
            stiffness,
            damping,
            steps,
            turns,
            polydyne,
        });
    }
    Ok(())
}

/// A non-empty list of finite numbers at `key` (or `default`), positive
/// or, without `positive`, zero or positive.
fn numbers(t: &mut Table, key: &str, default: Option<Vec<f64>>, positive: bool) -> R<Vec<f64>> {
    t.mark(key);
    let what = if positive {
        "positive"
    } else {
        "zero or positive"
    };
    let list = match (t.get(key), default) {
        (None, Some(d)) => return Ok(d),
        (None, None) => return t.fail(key, format!("is required: a list of {what} numbers")),
        (Some(v), _) => v,
    };
    let ok = |x: f64| x.is_finite() && if positive { x > 0.0 } else { x >= 0.0 };
    let read: Option<Vec<f64>> = match list {
        Value::Array(a) if !a.is_empty() => {
            a.iter().map(|x| number(x).filter(|&x| ok(x))).collect()
        }
        _ => None,
    };
    match read {
        Some(v) => Ok(v),
        None => t.fail(
            key,
            format!(
                "must be a list of {what} numbers, got {}",
                crate::table::repr(list)
            ),
        ),
    }
}

/// The largest follower displacement over a turn, sampled at
/// [`LIFT_SAMPLES`] angles from 0 to 2π (NaN when any sample is).
fn largest_lift(program: &Program) -> f64 {
    let n = LIFT_SAMPLES - 1;
    let step = TAU / n as f64;
    (0..=n)
        .map(|k| if k == n { TAU } else { k as f64 * step })
        .map(|t| program.eval(t)[0])
        .fold(f64::NEG_INFINITY, |m, s| {
            if m.is_nan() || s.is_nan() {
                f64::NAN
            } else {
                m.max(s)
            }
        })
}

/// The synthesised profile, sampled at [`PROFILE_SAMPLES`] angles, is
/// finite, clear of the bore and keyway, and larger than the export
/// tolerances can resolve.
fn check_profile(cam: &Cam, export: &Export) -> R<()> {
    let step = TAU / PROFILE_SAMPLES as f64;
    let points: Vec<[f64; 2]> = (0..PROFILE_SAMPLES)
        .map(|k| cam.offset_point(k as f64 * step, 0.0))
        .collect();
    if let Some(k) = points
        .iter()
        .position(|p| !(p[0].is_finite() && p[1].is_finite()))
    {
        return Err(Fail {
            field: None,
            message: format!(
                "the synthesised profile is not finite at θ = {:.2}° (check the base radius, \
                 the follower's dimensions, the lifts and the end conditions)",
                (k as f64 * step).to_degrees()
            ),
        });
    }
    let radii: Vec<f64> = points.iter().map(|p| p[0].hypot(p[1])).collect();
    if let Some(bore) = export.bore_radius {
        let least = radii.iter().copied().fold(f64::INFINITY, f64::min);
        let outer = bore + export.keyway_depth.unwrap_or(0.0);
        if outer >= least {
            return fail(
                "export.bore_diameter",
                format!(
                    "the bore and keyway reach {} m from the centre, beyond the profile's \
                     least radius {} m",
                    num(outer),
                    num(least)
                ),
            );
        }
    }
    // The exports' own bound (`export::check_tolerance`), on the curve
    // the tool path offsets furthest.
    let offset = export.tool_radius.unwrap_or(0.0);
    for (key, tol) in [
        ("tolerance", Some(export.tolerance)),
        ("csv_chord_tolerance", export.csv_chord),
    ] {
        if let Some(Err(message)) = tol.map(|t| crate::export::check_tolerance(cam, t, offset)) {
            return fail(format!("export.{key}"), message);
        }
    }
    Ok(())
}
