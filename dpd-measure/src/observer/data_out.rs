//! The last state of a run as a LAMMPS data file (`write_data = "FILE.data"`), written at the
//! run's last step (not after a blow-up or an interruption).

use super::interface::{Boxed, End, Observer, Setup};
use crate::data_file::data_of;
use crate::result::RunResult;
use crate::scene::output::run_path;
use dpd_core::{ParamError, System};
use std::path::PathBuf;

struct DataOut {
    path: PathBuf,
    steps: u64,
    title: String,
    /// The type names.
    names: Vec<String>,
}

pub(super) fn new<'a>(
    setup: &Setup<'a>,
    sys: &mut System,
) -> Result<Option<Boxed<'a>>, ParamError> {
    let Some(file) = &setup.scene.output.write_data else {
        return Ok(None);
    };
    let path = run_path(file, setup.seed, setup.scene.run.runs);
    if sys.walls().is_some() || sys.shear().is_some() {
        return Err(ParamError::new(
            "write_data",
            path.display(),
            "a data file holds a periodic box: not with [walls] or a shear rate",
        ));
    }
    let description = &setup.scene.output.description;
    let mut title = format!("dpd run, dt = {}, seed {}", setup.dt, setup.seed);
    if !description.is_empty() {
        title += &format!(": {description}");
    }
    Ok(Some(Box::new(DataOut {
        path,
        steps: setup.steps,
        title: title.replace('#', ""),
        names: setup.scene.type_names(sys.params().types()),
    })))
}

impl Observer for DataOut {
    fn next_stop(&self, _: u64) -> u64 {
        self.steps
    }

    fn after_steps(&mut self, sys: &mut System) -> Result<(), ParamError> {
        if sys.step() != self.steps {
            return Ok(());
        }
        let bad = |e: String| ParamError::new("write_data", self.path.display(), e);
        let data = data_of(sys, &self.names, &self.title).map_err(bad)?;
        data.write(&self.path).map_err(|e| bad(e.to_string()))
    }

    fn finish(self: Box<Self>, _: &mut System, _: &End, _: &mut RunResult) {}
}
