//! One population evaluated over the ranks of an MPI job (the `mpi` feature; these tests run
//! `mpirun` on this machine only): two and three ranks give the database of one process for
//! two encodings, two ranks for a run in habitats with noisy trials, and two and three for a
//! run whose creatures grow during their walks, developed and keyed by the ranks that walk
//! them; two ranks for continuous and direct genomes, a thrower's graph genomes and fresh
//! trials; a steady-state run over two and three ranks (births streamed to the ranks) for
//! L-system genomes, habitats with noisy trials and growing creatures; a killed worker rank
//! ends the job with a message and a nonzero exit code and `evolve --resume` (one process or
//! two ranks) then finishes the run, generational or steady-state, to the result of an
//! uninterrupted one, a rank 0 that refuses its input ends every rank, and a job launched
//! from a host file, as on a cluster, gives the run of one process.

use std::path::{Path, PathBuf};
use std::process::{Command, Output, Stdio};
use std::time::{Duration, Instant};

use crate::evolve::contents;
use crate::util::{evolve_walkers, ontogeny_command, refused, scratch_dir, succeeded};

/// A fresh, empty scratch directory of this module's, named after `name`.
fn scratch(name: &str) -> PathBuf {
    scratch_dir(&format!("mpi-{name}"))
}

/// `command` (an `ontogeny` command) started by `mpirun` as `ranks` processes on this machine
/// alone: more processes than cores allowed, waiting ranks yielding their core, root allowed.
fn under_mpirun(ranks: usize, command: &Command) -> Command {
    launched(&["--oversubscribe".as_ref()], ranks, command)
}

/// `command` started by `mpirun` with the launcher's arguments `launch` first, as `ranks`
/// processes over the loopback interface: waiting ranks yielding their core, root allowed.
fn launched(launch: &[&std::ffi::OsStr], ranks: usize, command: &Command) -> Command {
    let mut mpirun = Command::new("mpirun");
    mpirun
        .args(launch)
        .args(["--mca", "mpi_yield_when_idle", "1"])
        .args(["--mca", "btl", "self,vader,tcp"])
        .args(["--mca", "btl_tcp_if_include", "lo"])
        .args(["-np", &ranks.to_string()])
        .arg(command.get_program())
        .args(command.get_args())
        .env("OMPI_ALLOW_RUN_AS_ROOT", "1")
        .env("OMPI_ALLOW_RUN_AS_ROOT_CONFIRM", "1");
    mpirun
}

/// `ontogeny evolve` of `encoding` into `out`: walkers, 8 individuals, `gens` generations of
/// `seconds` s walks, seed 5.
fn evolve(encoding: &str, out: &Path, gens: &str, seconds: &str) -> Command {
    let mut command = evolve_walkers(encoding, "8");
    command
        .args(["--gens", gens, "--seconds", seconds, "--seed", "5", "--out"])
        .arg(out);
    command
}

/// The small run: 3 generations of 1 s walks.
fn small(encoding: &str, out: &Path) -> Command {
    evolve(encoding, out, "3", "1")
}

#[test]
fn two_and_three_ranks_give_the_run_of_one_process() {
    for encoding in ["lsystem", "graph"] {
        let dir = scratch(&format!("ranks-{encoding}"));
        let one = dir.join("one");
        let alone = succeeded(&small(encoding, &one).output().unwrap());
        for ranks in [2, 3] {
            let many = dir.join(format!("ranks-{ranks}"));
            let output = under_mpirun(ranks, &small(encoding, &many))
                .output()
                .unwrap();
            let printed = succeeded(&output);
            // Rank 0 alone speaks: its results, not one copy per rank.
            assert_eq!(
                printed.lines().count(),
                alone.lines().count(),
                "{encoding}, {ranks} ranks: {printed}"
            );
            assert_eq!(contents(&one), contents(&many), "{encoding}, {ranks} ranks");
        }
        let _ = std::fs::remove_dir_all(dir);
    }
}

#[test]
fn a_run_in_habitats_with_noisy_trials_over_two_ranks_is_the_run_of_one_process() {
    let dir = scratch("habitats");
    // Two habitats of two arrays, two noisy trials each: every walk a unit sent to a rank.
    let run = |out: &Path| {
        let mut command = ontogeny_command();
        command
            .args(["evolve", "--config", "examples/habitats.toml"])
            .args(["--pop", "6", "--gens", "2", "--seconds", "0.5", "--out"])
            .arg(out);
        command
    };
    let one = dir.join("one");
    succeeded(&run(&one).output().unwrap());
    let two = dir.join("two");
    succeeded(&under_mpirun(2, &run(&two)).output().unwrap());
    assert_eq!(contents(&one), contents(&two));
    let _ = std::fs::remove_dir_all(dir);
}

#[test]
fn workers_develop_and_key_what_they_walk_and_a_growing_run_is_the_run_of_one_process() {
    let dir = scratch("growing");
    // Creatures that go on growing during their walks: each rank develops its share of the
    // births, walks what it holds, and takes over another's walk by developing it again.
    let run = |out: &Path| {
        let mut command = ontogeny_command();
        command
            .args(["evolve", "--config", "examples/evolve-while-growing.toml"])
            .args([
                "--pop",
                "6",
                "--gens",
                "2",
                "--seconds",
                "0.5",
                "--seed",
                "3",
            ])
            .arg("--out")
            .arg(out);
        command
    };
    let one = dir.join("one");
    succeeded(&run(&one).output().unwrap());
    for ranks in [2, 3] {
        let many = dir.join(format!("ranks-{ranks}"));
        let mut command = under_mpirun(ranks, &run(&many));
        let output = command.env("ONTOGENY_MPI_TIMING", "1").output().unwrap();
        succeeded(&output);
        assert_eq!(contents(&one), contents(&many), "{ranks} ranks");
        // Rank 0's figures: the other ranks developed births and walked them.
        let line = timing_line(&output);
        assert!(
            count(&line, "births developed on other ranks,") > 0,
            "{line}"
        );
        assert!(count(&line, "walks on other ranks,") > 0, "{line}");
    }
    let _ = std::fs::remove_dir_all(dir);
}

/// Rank 0's line of figures (`ONTOGENY_MPI_TIMING`) in a job's `output`.
fn timing_line(output: &Output) -> String {
    let stderr = String::from_utf8_lossy(&output.stderr);
    stderr
        .lines()
        .find(|l| l.starts_with("MPI: "))
        .unwrap_or_else(|| panic!("no MPI line: {stderr}"))
        .to_string()
}

/// The number before the words `after` in rank 0's line of figures `line`.
fn count(line: &str, after: &str) -> u64 {
    let words: Vec<&str> = line.split(' ').collect();
    let at = words
        .windows(after.split(' ').count())
        .position(|w| w.join(" ") == after)
        .unwrap_or_else(|| panic!("{after:?} not in {line}"));
    words[at - 1].trim_start_matches('(').parse().unwrap()
}

/// `command` as a steady-state run with `in_flight` births in flight.
fn steady(mut command: Command, in_flight: &str) -> Command {
    command.args(["--algorithm", "steady-state", "--in-flight", in_flight]);
    command
}

#[test]
fn a_steady_state_run_over_two_and_three_ranks_is_the_run_of_one_process() {
    let dir = scratch("steady");
    // Births streamed to the ranks as they fall free: L-system genomes (the cache lends stored
    // creatures their evaluations; the workers skip walking those), creatures in habitats
    // with noisy trials (each birth's walks combined on its rank), and creatures that grow
    // during their walks; those two write a profile as they go (rank 0 stores each
    // generation while it streams the births).
    let config_run = |config: &'static str, seed: &'static str| {
        move |out: &Path| {
            let mut command = ontogeny_command();
            command
                .args(["evolve", "--config", config])
                .args(["--pop", "6", "--gens", "3", "--seconds", "0.5"])
                .args(["--seed", seed, "--out"])
                .arg(out)
                .arg("--profile")
                .arg(out.with_extension("jsonl"));
            steady(command, "4")
        }
    };
    let runs: Vec<(&str, Box<Run<'_>>, &[usize])> = vec![
        (
            "lsystem",
            Box::new(|out| steady(evolve("lsystem", out, "5", "0.5"), "3")),
            &[2, 3],
        ),
        (
            "habitats",
            Box::new(config_run("examples/habitats.toml", "1")),
            &[2],
        ),
        (
            "growing",
            Box::new(config_run("examples/evolve-while-growing.toml", "3")),
            &[2],
        ),
    ];
    let mut stored_elsewhere = 0;
    for (name, run, ranks) in runs {
        let one = dir.join(format!("{name}-one"));
        succeeded(&run(&one).output().unwrap());
        let plot = std::fs::read_to_string(one.join("fitness.svg")).unwrap();
        assert!(plot.contains("steady-state ("), "{name}: {plot}");
        for &ranks in ranks {
            let many = dir.join(format!("{name}-{ranks}"));
            let mut command = under_mpirun(ranks, &run(&many));
            let output = command.env("ONTOGENY_MPI_TIMING", "1").output().unwrap();
            succeeded(&output);
            assert_eq!(contents(&one), contents(&many), "{name}, {ranks} ranks");
            let line = timing_line(&output);
            assert!(
                count(&line, "steady-state births made on other ranks") > 0,
                "{name}: {line}"
            );
            stored_elsewhere += count(&line, "of them found stored, not walked;");
        }
    }
    // Among the L-system runs' stored creatures, some were bred on other ranks.
    assert!(stored_elsewhere > 0);
    let _ = std::fs::remove_dir_all(dir);
}

/// A run's command, given its output directory.
type Run<'a> = dyn Fn(&Path) -> Command + 'a;

#[test]
fn other_encodings_a_thrower_and_fresh_trials_over_two_ranks_are_the_run_of_one_process() {
    let dir = scratch("kinds");
    // Fresh trials: the draws change every generation, and the cache reuses an evaluation
    // only within it.
    let habitats = std::fs::read_to_string("examples/habitats.toml").unwrap();
    let fresh = dir.join("fresh.toml");
    std::fs::write(
        &fresh,
        habitats.replace("[task.trials]\n", "[task.trials]\nfresh = true\n"),
    )
    .unwrap();
    assert!(
        std::fs::read_to_string(&fresh)
            .unwrap()
            .contains("fresh = true")
    );
    let runs: Vec<(&str, Box<Run<'_>>)> = vec![
        (
            "continuous",
            Box::new(|out| evolve("lsystem-continuous", out, "2", "0.5")),
        ),
        ("direct", Box::new(|out| evolve("direct", out, "2", "0.5"))),
        (
            // Graph genomes of a thrower: their limits keep the root as an arm.
            "catapult",
            Box::new(|out| {
                let mut command = ontogeny_command();
                command
                    .args(["evolve", "--config", "examples/evolve-catapult.toml"])
                    .args(["--pop", "8", "--gens", "2", "--seed", "2", "--out"])
                    .arg(out);
                command
            }),
        ),
        (
            "fresh",
            Box::new(|out| {
                let mut command = ontogeny_command();
                command
                    .args(["evolve", "--config"])
                    .arg(&fresh)
                    .args(["--pop", "6", "--gens", "3", "--seconds", "0.5", "--out"])
                    .arg(out);
                command
            }),
        ),
    ];
    for (name, run) in runs {
        let one = dir.join(format!("{name}-one"));
        succeeded(&run(&one).output().unwrap());
        let two = dir.join(format!("{name}-two"));
        succeeded(&under_mpirun(2, &run(&two)).output().unwrap());
        assert_eq!(contents(&one), contents(&two), "{name}");
    }
    let _ = std::fs::remove_dir_all(dir);
}

/// The run the kill test interrupts: long enough to be killed in its middle.
fn long(out: &Path) -> Command {
    evolve("lsystem", out, "6", "4")
}

/// The process id of the rank `rank` of the job whose ranks run `binary` with `out` among
/// their arguments, once it exists.
fn rank_process(out: &Path, rank: u32) -> Option<u32> {
    let wanted = format!("OMPI_COMM_WORLD_RANK={rank}");
    std::fs::read_dir("/proc").ok()?.find_map(|entry| {
        let pid: u32 = entry.ok()?.file_name().to_str()?.parse().ok()?;
        let command_line = std::fs::read(format!("/proc/{pid}/cmdline")).ok()?;
        let environment = std::fs::read(format!("/proc/{pid}/environ")).ok()?;
        let is_rank = String::from_utf8_lossy(&command_line)
            .split('\0')
            .any(|a| Path::new(a) == out)
            && String::from_utf8_lossy(&environment)
                .split('\0')
                .any(|v| v == wanted);
        is_rank.then_some(pid)
    })
}

#[test]
fn a_killed_worker_rank_ends_the_job_and_the_run_resumes_to_the_same_result() {
    killed_and_resumed("kill", &long);
}

#[test]
fn a_steady_state_run_killed_over_three_ranks_resumes_to_the_same_result() {
    killed_and_resumed("kill-steady", &|out| steady(long(out), "3"));
}

/// `run` started over three ranks, its rank 2 killed while generation 2 is evaluated: the job
/// ends with a message, and the run resumed by one process, or by two ranks, is the run
/// uninterrupted.
fn killed_and_resumed(name: &str, run: &Run<'_>) {
    let dir = scratch(name);
    let whole = dir.join("whole");
    succeeded(&run(&whole).output().unwrap());
    let killed = dir.join("killed");
    let job = under_mpirun(3, &run(&killed))
        .stdout(Stdio::null())
        .stderr(Stdio::piped())
        .spawn()
        .unwrap();
    // Once generation 1 is stored, SIGKILL rank 2 while generation 2 is evaluated.
    let log = killed.join("log.txt");
    let deadline = Instant::now() + Duration::from_secs(120);
    while std::fs::read_to_string(&log).map_or(0, |t| t.lines().count()) < 2
        && Instant::now() < deadline
    {
        std::thread::sleep(Duration::from_millis(2));
    }
    let worker = rank_process(&killed, 2).expect("rank 2 runs");
    let status = Command::new("kill")
        .args(["-9", &worker.to_string()])
        .status()
        .unwrap();
    assert!(status.success());
    let ended: Output = job.wait_with_output().unwrap();
    assert!(!ended.status.success());
    let said = String::from_utf8_lossy(&ended.stderr);
    assert!(
        said.contains("rank 2") && said.contains("signal 9"),
        "{said}"
    );
    let store = ontogeny::run::store::RunStore::open(&killed.join("run.sqlite")).unwrap();
    let stored = store.last_generation().unwrap();
    drop(store);
    assert!(
        stored.is_some_and(|g| g < 5),
        "killed before the end: {stored:?}"
    );
    // The run store is the checkpoint: resumed by one process, or by two ranks.
    let copy = dir.join("copy");
    std::fs::create_dir(&copy).unwrap();
    for file in std::fs::read_dir(&killed).unwrap() {
        let file = file.unwrap();
        std::fs::copy(file.path(), copy.join(file.file_name())).unwrap();
    }
    let mut resume = ontogeny_command();
    resume.arg("evolve").arg("--resume").arg(&killed);
    succeeded(&resume.output().unwrap());
    assert_eq!(contents(&whole), contents(&killed));
    let mut resume = ontogeny_command();
    resume.arg("evolve").arg("--resume").arg(&copy);
    succeeded(&under_mpirun(2, &resume).output().unwrap());
    assert_eq!(contents(&whole), contents(&copy));
    let _ = std::fs::remove_dir_all(dir);
}

#[test]
fn a_rank_0_that_refuses_its_input_ends_every_rank_with_exit_code_2() {
    let dir = scratch("refused");
    let mut resume = ontogeny_command();
    resume
        .arg("evolve")
        .arg("--resume")
        .arg(dir.join("missing"));
    let output = under_mpirun(3, &resume).output().unwrap();
    refused(&output, "missing");
}

/// A job launched as on a cluster: `mpirun --hostfile` with a host file naming the machines and
/// the ranks each may run (here this machine alone, by its loopback name, three slots, so no
/// oversubscription is asked for) gives the run of one process.
#[test]
fn a_job_launched_from_a_host_file_gives_the_run_of_one_process() {
    let dir = scratch("hostfile");
    let hosts = dir.join("hosts");
    std::fs::write(&hosts, "localhost slots=3\n").unwrap();
    let one = dir.join("one");
    succeeded(&small("lsystem", &one).output().unwrap());
    let many = dir.join("from-hosts");
    let command = small("lsystem", &many);
    let output = launched(&["--hostfile".as_ref(), hosts.as_os_str()], 3, &command)
        .output()
        .unwrap();
    succeeded(&output);
    assert_eq!(contents(&one), contents(&many));
    let _ = std::fs::remove_dir_all(dir);
}
