//! Criterion benches of jbearing, one binary: kernel, sweep and cycle groups.
use criterion::{Criterion, criterion_group, criterion_main};

mod inverse;
mod kernel;
mod mobility;
mod reynolds;

// The line kernels are timed in thread CPU time (see benches/kernel.rs): on a shared machine the
// wall time of a microsecond kernel mostly measures the other processes.
criterion_group! {
    name = kernel_benches;
    config = Criterion::default().with_measurement(kernel::ThreadCpuTime);
    targets = kernel::bench
}
criterion_group!(benches, mobility::bench, reynolds::bench, inverse::bench);
criterion_main!(kernel_benches, benches);
