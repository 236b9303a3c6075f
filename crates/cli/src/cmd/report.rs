//! `iridis report FILE -o DIR`: from a new scan to its colours in one command (`iridis_api::scan_report`, which
//! runs the steps a user would type and records each with its command line).

use anyhow::Result;
use clap::Args as ClapArgs;
use iridis_api::scan_report::{write_report, ReportOptions};
use iridis_api::Report as _;

use crate::progress::Cli;

#[derive(Debug, ClapArgs)]
#[command(after_help = "\
Steps (each a command shown in the report, run with the same surface options):
  1. iridis surface info FILE --level L --image relief.png --psdf psdf.png --acf acf.png --json
     size, heights, roughness (Sq, Sa, Ssk, Sku, correlation length), periods and orientations, PSDF, ACF
  2. iridis grating FILE --light 0deg / 45deg --from 380nm --to 780nm --orders-above 0.01: the scan as
     one unit cell, how much of the light it diffracts and the colour of its mirror reflection
  3. iridis brdf-map FILE --method reference --incidence 0deg / 45deg --auto-exposure, under D65: the
     structure's colours (only when it diffracts at least 0.1 % of the reflected light)
  4. iridis brdf vision FILE --visual bluetit --strip vision.png: how a bird (--visual) sees the colours
     in each direction of the plane of the strongest period, ΔS in JND against the mirror direction
  5. iridis grating FILE --unit-cell auto --compare: how far the scalar model behind the maps is from
     Maxwell's equations (the C-method) on the scan's own profile (likewise)
  6. iridis testbench FILE --json --plot testbench.png: the period from the grating equation (paper 6.1),
     along the orientation of the strongest period (likewise)
The report opens with a sentence on what the scan does to visible light. Warnings (pixels too coarse for
the visible band, units assumed, NaN lines) are collected with their numbers. Files are plane-levelled
unless --level says otherwise.

Examples:
  iridis report scan.spm -o scan_report
  iridis report scan.jpk --channel height_trace --size 96 -o jpk_report
  iridis report scan.npy --pixel-size 5nm --height-unit m --level lines -o npy_report")]
pub struct ReportArgs {
    #[command(flatten)]
    pub options: ReportOptions,
}

pub fn run(a: ReportArgs) -> Result<()> {
    let r = write_report(&a.options, Some(&step_inputs), &Cli)?;
    crate::outln!("{}", r.text().trim_end_matches('\n'))?;
    r.warnings.iter().for_each(|w| Cli.warn(w));
    Ok(())
}

/// The options a step's command line gives its command, as that command's `--json` shows them (`"inputs"`).
fn step_inputs(args: &[String]) -> Option<serde_json::Value> {
    use clap::CommandFactory;
    let cmd = crate::Cli::command();
    let m = cmd.clone().try_get_matches_from(std::iter::once("iridis").chain(args.iter().map(String::as_str))).ok()?;
    Some(crate::output::inputs_of(&cmd, &m))
}
