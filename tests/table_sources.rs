//! `CombiTimeTable`: interpolation, extrapolation, jumps and time events, from a table
//! given as rows or read from a file (MSL's text format and CSV).

#![allow(missing_docs)]

use std::path::PathBuf;

use multibody::blocks::{CombiTimeTable, Extrapolation, Smoothness};
use multibody::prelude::*;

fn data(name: &str) -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR"))
        .join("tests/data/tables")
        .join(name)
}

fn parabola() -> Vec<Vec<f64>> {
    vec![
        vec![0.0, 0.0],
        vec![1.0, 0.0],
        vec![1.0, 1.0],
        vec![2.0, 4.0],
        vec![3.0, 9.0],
        vec![4.0, 16.0],
    ]
}

fn solve(table: CombiTimeTable, t_end: f64) -> Solution {
    let mut model = System::new("table");
    model.add("table", &table);
    let ssys = structural_simplify(&model).unwrap();
    DaeProblem::new(&ssys, &[], (0.0, t_end))
        .unwrap()
        .solve(&SolverOptions::default())
        .unwrap()
}

#[test]
fn msl_documentation_example_from_rows_and_from_files() {
    // MSL's documented values: 2.5 at 1.5, 4 at 2, 23 at 5 (through the last two rows);
    // at 1 a jump from 0 to 1.
    let from_rows = CombiTimeTable {
        table: parabola(),
        ..CombiTimeTable::default()
    };
    let from_text = CombiTimeTable {
        file: Some(data("parabola.txt")),
        table_name: "tab1".into(),
        ..CombiTimeTable::default()
    };
    let from_csv = CombiTimeTable {
        file: Some(data("parabola.csv")),
        ..CombiTimeTable::default()
    };
    for table in [from_rows, from_text, from_csv] {
        let sol = solve(table, 5.0);
        for (t, y) in [
            (0.5, 0.0),
            (1.5, 2.5),
            (2.0, 4.0),
            (2.5, 6.5),
            (3.5, 12.5),
            (5.0, 23.0),
        ] {
            let got = sol.at("table.y", t).unwrap();
            assert!((got - y).abs() < 1e-12, "y({t}) = {got}, exact {y}");
        }
        // The jump at 1 is an event with both limits; each row's time is an event.
        let times: Vec<f64> = sol.events().iter().map(|e| e.t).collect();
        for t in [1.0, 2.0, 3.0] {
            assert!(times.contains(&t), "no event at {t}: {times:?}");
        }
        let at_one: Vec<f64> = (0..sol.t().len())
            .filter(|&i| sol.t()[i] == 1.0)
            .map(|i| sol.get("table.y").unwrap()[i])
            .collect();
        assert_eq!(at_one, vec![0.0, 1.0]);
    }
}

#[test]
fn constant_segments_hold_and_periodic_tables_repeat() {
    let rows = vec![vec![0.0, 1.0], vec![1.0, 3.0], vec![2.0, 2.0]];
    let held = solve(
        CombiTimeTable {
            table: rows.clone(),
            smoothness: Smoothness::ConstantSegments,
            extrapolation: Extrapolation::HoldLastPoint,
            offset: 10.0,
            ..CombiTimeTable::default()
        },
        4.0,
    );
    for (t, y) in [(0.5, 11.0), (1.5, 13.0), (2.5, 12.0), (4.0, 12.0)] {
        assert_eq!(held.at("table.y", t).unwrap(), y, "at {t}");
    }
    // Periodic with period 2: linear 1 -> 3 -> 2, again from 1 at 2, 4, ...
    let periodic = solve(
        CombiTimeTable {
            table: rows,
            extrapolation: Extrapolation::Periodic,
            ..CombiTimeTable::default()
        },
        5.0,
    );
    for (t, y) in [(0.5, 2.0), (1.5, 2.5), (2.5, 2.0), (3.25, 2.75), (4.5, 2.0)] {
        let got = periodic.at("table.y", t).unwrap();
        assert!((got - y).abs() < 1e-12, "y({t}) = {got}, exact {y}");
    }
    // Time scaling and a start time: the table's times in minutes from 10 s.
    let scaled = solve(
        CombiTimeTable {
            table: parabola(),
            time_scale: 60.0,
            start_time: 10.0,
            ..CombiTimeTable::default()
        },
        200.0,
    );
    assert_eq!(scaled.at("table.y", 5.0).unwrap(), 0.0);
    assert!((scaled.at("table.y", 10.0 + 90.0).unwrap() - 2.5).abs() < 1e-12);
}

#[test]
fn a_missing_file_or_column_is_an_error_naming_the_table() {
    let mut model = System::new("bad");
    model.add(
        "source",
        &CombiTimeTable {
            file: Some(data("missing.csv")),
            ..CombiTimeTable::default()
        },
    );
    let err = structural_simplify(&model).unwrap_err().to_string();
    assert!(
        err.contains("source") && err.contains("missing.csv"),
        "{err}"
    );
    let mut model = System::new("bad_column");
    model.add(
        "source",
        &CombiTimeTable {
            table: parabola(),
            column: 3,
            ..CombiTimeTable::default()
        },
    );
    let err = structural_simplify(&model).unwrap_err().to_string();
    assert!(err.contains("source") && err.contains("column 3"), "{err}");
}
