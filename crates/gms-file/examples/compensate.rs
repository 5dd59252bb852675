//! A compensator built from a model file, run along a signal read from standard input, one
//! force a line on standard output: what a Rust loop gets from an identified file.
//!
//! ```text
//! cargo run -p gms-file --example compensate -- MODEL.json DT observer < positions
//! cargo run -p gms-file --example compensate -- MODEL.json DT feedforward X0 < velocity,position
//! ```
//!
//! Observer mode reads a position a line, feedforward mode a velocity and a position; X0 places
//! a feedforward compensator's position terms. Each force is printed in the shortest form that
//! reads back as the same double, so that a caller compares it bit for bit. A refusal is one
//! line on standard error, and the exit status is 1.

use std::io::{self, BufRead, BufWriter, Write};
use std::process::ExitCode;

use gms_core::Mode;
use gms_dyn::{Compensator, Terms};
use gms_file::ModelFile;

const USAGE: &str = "usage: compensate MODEL.json DT observer|feedforward [X0] < signal";

fn main() -> ExitCode {
    match run() {
        Ok(()) => ExitCode::SUCCESS,
        Err(reason) => {
            eprintln!("compensate: {reason}");
            ExitCode::FAILURE
        }
    }
}

/// `text` as a number, or a refusal that names `what` and shows what it got.
fn number(what: &str, text: &str) -> Result<f64, String> {
    text.trim()
        .parse()
        .map_err(|_| format!("{what} must be a number, got {text:?}"))
}

fn run() -> Result<(), Box<dyn std::error::Error>> {
    let arguments: Vec<String> = std::env::args().skip(1).collect();
    let [path, dt, mode, rest @ ..] = arguments.as_slice() else {
        return Err(USAGE.into());
    };
    let mode = match mode.as_str() {
        "observer" => Mode::Observer,
        "feedforward" => Mode::Feedforward,
        _ => {
            return Err(
                format!("mode must be observer or feedforward, got {mode:?}; {USAGE}").into(),
            )
        }
    };
    let start = rest.first().map(|x| number("X0", x)).transpose()?;
    let model = ModelFile::load(path)?.validate()?;
    let terms = Terms {
        start,
        level: model.level,
        position_force: model.position_force,
    };
    let mut compensator = Compensator::with_terms(&model.params, number("DT", dt)?, mode, &terms)?;
    let width = if mode == Mode::Feedforward { 2 } else { 1 };
    let mut out = BufWriter::new(io::stdout().lock());
    for (index, line) in io::stdin().lock().lines().enumerate() {
        let line = line?;
        let what = format!("line {} of the signal", index + 1);
        let values = line
            .split(',')
            .map(|value| number(&what, value))
            .collect::<Result<Vec<_>, _>>()?;
        let force = match *values.as_slice() {
            [v, x] if width == 2 => compensator.step_trajectory(v, x)?,
            [x] if width == 1 => compensator.step(x)?,
            _ => {
                return Err(
                    format!("{what} must hold {width} number(s), got {line:?}; {USAGE}").into(),
                )
            }
        };
        writeln!(out, "{force:?}")?;
    }
    Ok(())
}
