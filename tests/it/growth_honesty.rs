//! Growth is not a motor: a champion that evolved to exploit growth as one (in a release where
//! new mass arrived moving with its parent and kept that speed, and where a new part could
//! appear inside another) walks no further than honest creatures do, and its growth never
//! gives it kinetic energy.

use crate::util::ontogeny_ok;

/// The fixture's evaluation, as `eval --json` prints it.
fn evaluated() -> serde_json::Value {
    let out = ontogeny_ok(&["eval", "tests/fixtures/growth-motor.lsys", "--json"]);
    serde_json::from_slice(&out.stdout).unwrap()
}

#[test]
fn a_champion_that_used_growth_as_a_motor_walks_no_more_than_a_few_metres() {
    let json = evaluated();
    assert_eq!(json["status"], "ok");
    // It recorded 114.4 m in 10 s when growth was a motor; the evolved honest walkers of the
    // same experiment's "before" condition reach about 10 m.
    let walked = json["terms"]["D_w"].as_f64().unwrap();
    assert!(walked < 3.0, "it walked {walked} m in 10 s");
    // It still grows during the walk, but its chain of parts would appear inside a part it
    // grew earlier (the development keeps what the new string no longer builds, and the
    // string puts the chain where that part is): the chain waits, the whole walk long.
    assert_eq!(json["terms"]["grown_parts"].as_f64(), Some(2.0));
    assert!(json["terms"]["growth_stopped"].as_f64().unwrap() > 100.0);
    // The energy growth brought is the weight it lifted: far below the 1.45 MJ it was.
    let work = json["terms"]["growth_work"].as_f64().unwrap();
    assert!(work < 20_000.0, "growth did {work} J of work");
}
