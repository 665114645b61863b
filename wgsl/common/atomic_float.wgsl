// vsgl:include-only
// Float addition into storage words (WGSL has no float atomics): a compare-exchange loop on the
// value's bits. The including shader declares `float_sums: array<atomic<u32>>`. The order in
// which threads add is not fixed, so sums may differ in their last bits from run to run.
fn atomic_add_float(i: u32, value: f32) {
    if (value == 0.0) {
        return;
    }
    var old = atomicLoad(&float_sums[i]);
    loop {
        let r = atomicCompareExchangeWeak(&float_sums[i], old, bitcast<u32>(bitcast<f32>(old) + value));
        if (r.exchanged) {
            break;
        }
        old = r.old_value;
    }
}
