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
        ..DeriveOptions::default()
    };
    match lsys.derivation(&options) {
        Ok(mut derivation) => {
            for _ in 0..5 {
                if let Err(e) = derivation.step() {
                    let _ = e.to_string();
                    break;
                }
            }
            if let Err(e) = lsys.interpret(derivation.current(), 0.0, &options) {
                let _ = e.to_string();
            }
        }
        Err(e) => {
            let _ = e.to_string();
        }
    }
    // Continuous development (files with `time:`): a few observation steps.
    if lsys.is_continuous() {
        match lsys.development(&options) {
            Ok(mut dev) => {
                for _ in 0..5 {
                    match dev.advance() {
                        Ok(true) => {}
                        Ok(false) => break,
                        Err(e) => {
                            let _ = e.to_string();
                            break;
                        }
                    }
                }
                let _ = dev.take_events();
            }
            Err(e) => {
                let _ = e.to_string();
            }
        }
    }
});
