// Only the kicks B and F select a force group; a drift moves every particle.
fn main() {
    let _ = dpd::dpd_scheme!("A[pair] B O B A");
}
