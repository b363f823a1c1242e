#![no_main]

use libfuzzer_sys::fuzz_target;
use ontogeny::lsystem::{DeriveOptions, LSystem};

fuzz_target!(|data: &[u8]| {
    let Ok(text) = std::str::from_utf8(data) else {
        return;
    };
    let lsys = match LSystem::from_text("fuzz.lsys", text) {
        Ok(lsys) => lsys,
        Err(e) => {
            let _ = e.to_string();
            return;
        }
    };
    let _ = lsys.check();
    let options = DeriveOptions {
        seed: None,
        max_modules: 10_000,
    };
    let mut derivation = lsys.derivation(&options);
    for _ in 0..5 {
        if let Err(e) = derivation.step() {
            let _ = e.to_string();
            break;
        }
    }
    if let Err(e) = lsys.interpret(derivation.current(), 0.0, &options) {
        let _ = e.to_string();
    }
});
