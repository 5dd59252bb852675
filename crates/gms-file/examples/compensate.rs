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
//! reads back as the same double, so that a caller compares it bit for bit.

use std::io::{self, BufRead, BufWriter, Write};

use gms_core::Mode;
use gms_dyn::{Compensator, Terms};
use gms_file::ModelFile;

const USAGE: &str = "usage: compensate MODEL.json DT observer|feedforward [X0] < signal";

fn main() -> Result<(), Box<dyn std::error::Error>> {
    let arguments: Vec<String> = std::env::args().skip(1).collect();
    let [path, dt, mode, rest @ ..] = arguments.as_slice() else {
        return Err(USAGE.into());
    };
    let mode = match mode.as_str() {
        "observer" => Mode::Observer,
        "feedforward" => Mode::Feedforward,
        _ => return Err(USAGE.into()),
    };
    let start = rest.first().map(|x| x.parse::<f64>()).transpose()?;
    let model = ModelFile::load(path)?.validate()?;
    let terms = Terms {
        start,
        level: model.level,
        position_force: model.position_force,
    };
    let mut compensator = Compensator::with_terms(&model.params, dt.parse()?, mode, &terms)?;
    let mut out = BufWriter::new(io::stdout().lock());
    for line in io::stdin().lock().lines() {
        let line = line?;
        let values = line
            .split(',')
            .map(|value| value.trim().parse::<f64>())
            .collect::<Result<Vec<_>, _>>()?;
        let force = match (mode, values.as_slice()) {
            (Mode::Feedforward, &[v, x]) => compensator.step_trajectory(v, x)?,
            (Mode::Observer, &[x]) => compensator.step(x)?,
            _ => return Err(format!("{line:?}: {USAGE}").into()),
        };
        writeln!(out, "{force:?}")?;
    }
    Ok(())
}
