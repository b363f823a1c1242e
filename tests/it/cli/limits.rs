//! Limits and refusals at the command line: a growth of a billion frames, a creature over
//! `--max-parts`, outputs that are directories or sockets, and `--activation` checked.

use super::*;

#[test]
fn a_growth_of_a_billion_frames_is_refused_at_once_when_its_frames_are_written() {
    let dir = scratch("billion-frames");
    let file = dir.join("long.lsys");
    std::fs::write(
        &file,
        "axiom: forward(1)\nderivation length: 1000000000\nforward(x) --> forward(x)\n",
    )
    .unwrap();
    let out = dir.join("out");
    let o = ontogeny(&[
        "grow",
        file.to_str().unwrap(),
        "--out",
        out.to_str().unwrap(),
    ]);
    let said = refused(&o, "1000000001 frames");
    assert!(said.contains("--steps"), "{said}");
    assert!(!out.exists(), "nothing is written");
    // --steps brings it within the limit; without --out only the last frame is kept.
    let o = ontogeny(&["grow", file.to_str().unwrap(), "--steps", "20000"]);
    assert!(o.status.success(), "{}", stderr(&o));
    assert!(stdout(&o).contains("in 20001 frames"), "{}", stdout(&o));
    let _ = std::fs::remove_dir_all(&dir);
}

#[test]
fn a_creature_file_with_more_parts_than_max_parts_is_refused_by_eval_and_export() {
    let dir = scratch("too-many-parts");
    let file = dir.join("chain.lsys");
    std::fs::write(
        &file,
        "axiom: { forward(0.5) }(100) { forward(0.5) }(100) forward(0.5)\n",
    )
    .unwrap();
    let out = dir.join("grown");
    let o = ontogeny(&[
        "grow",
        file.to_str().unwrap(),
        "--max-parts",
        "201",
        "--out",
        out.to_str().unwrap(),
    ]);
    assert!(o.status.success(), "{}", stderr(&o));
    let creature = out.join("creature.json");
    let creature = creature.to_str().unwrap();
    for args in [
        &["eval", creature, "--task", "walker"][..],
        &["export", creature],
    ] {
        assert_bad_input(args, "201 parts, more than the 200 allowed (--max-parts)");
    }
    // --max-parts lifts the limit.
    let o = ontogeny(&["export", creature, "--max-parts", "201"]);
    assert!(o.status.success(), "{}", stderr(&o));
    let _ = std::fs::remove_dir_all(&dir);
}

#[test]
fn export_refuses_an_out_that_is_a_directory_and_leaves_it_intact() {
    let dir = scratch("export-out-directory");
    let taken = dir.join("model.xml");
    std::fs::create_dir(&taken).unwrap();
    std::fs::write(taken.join("kept"), "kept").unwrap();
    let out = ontogeny(&[
        "export",
        "examples/snake.lsys",
        "--out",
        taken.to_str().unwrap(),
    ]);
    refused(
        &out,
        &format!(
            "{} exists and is not a regular file; refusing to replace it",
            taken.display()
        ),
    );
    assert_eq!(std::fs::read_to_string(taken.join("kept")).unwrap(), "kept");
    // A regular file is replaced whole, and nothing is left beside it.
    let file = dir.join("model-file.xml");
    std::fs::write(&file, "old").unwrap();
    let out = ontogeny(&[
        "export",
        "examples/snake.lsys",
        "--out",
        file.to_str().unwrap(),
    ]);
    assert!(out.status.success(), "{}", stderr(&out));
    assert!(std::fs::read_to_string(&file).unwrap().contains("<mujoco"));
    assert_eq!(std::fs::read_dir(&dir).unwrap().count(), 2);
}

#[cfg(unix)]
#[test]
fn eval_record_refuses_a_socket_before_evaluating_and_leaves_it_in_place() {
    use std::os::unix::fs::FileTypeExt;
    let dir = scratch("record-socket");
    // A recording's folder (one of the user's files would be refused as theirs).
    ontogeny::output::prepare_folder(&dir, ontogeny::output::FolderKind::Recording).unwrap();
    let socket = dir.join("behaviour.gif");
    let _listener = std::os::unix::net::UnixListener::bind(&socket).unwrap();
    let out = ontogeny(&[
        "eval",
        "examples/snake.lsys",
        "--task",
        "walker",
        "--seconds",
        "1",
        "--record",
        dir.to_str().unwrap(),
    ]);
    refused(&out, "behaviour.gif exists and is not a regular file");
    assert!(
        std::fs::symlink_metadata(&socket)
            .unwrap()
            .file_type()
            .is_socket()
    );
    // Refused before anything was evaluated or written.
    assert!(!dir.join("recording.json").exists());
    assert!(stdout(&out).is_empty(), "{}", stdout(&out));
}

#[test]
fn grow_out_refuses_a_picture_that_is_a_directory_and_writes_nothing() {
    let dir = scratch("grow-out-directory");
    // A growth's folder (one of the user's files would be refused as theirs).
    ontogeny::output::prepare_folder(&dir, ontogeny::output::FolderKind::Growth).unwrap();
    std::fs::create_dir(dir.join("creature.png")).unwrap();
    assert_bad_input(
        &[
            "grow",
            "examples/snake.lsys",
            "--out",
            dir.to_str().unwrap(),
        ],
        "creature.png exists and is not a regular file",
    );
    assert!(dir.join("creature.png").is_dir());
    assert!(!dir.join("creature.json").exists());
}

#[test]
fn eval_activation_sets_the_walker_s_first_activation_and_is_checked() {
    let file = "tests/fixtures/late-toppler.lsys";
    let fitness = |extra: &[&str]| -> f64 {
        let mut args = vec!["eval", file, "--task", "walker", "--fitness", "distance"];
        args.extend_from_slice(extra);
        let o = ontogeny(&args);
        assert!(o.status.success(), "{}", stderr(&o));
        let out = stdout(&o);
        let line = out.lines().next().unwrap();
        line.split("fitness ")
            .nth(1)
            .unwrap()
            .split(' ')
            .next()
            .unwrap()
            .parse()
            .unwrap()
    };
    // The default (1 s): toppled before the walk; 9 steps: toppled during it.
    assert!(fitness(&[]) < 0.01);
    assert!(fitness(&["--activation", "0.15"]) > 0.5);
    assert_bad_input(
        &["eval", file, "--task", "walker", "--activation", "-1"],
        "--activation",
    );
}
