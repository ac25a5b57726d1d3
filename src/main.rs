//! The `dpd` command-line program.

fn main() {
    eprintln!("dpd: the command-line program is under construction");
}
