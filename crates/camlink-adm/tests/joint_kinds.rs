//! The course-file types of the joint-kind registry (`JOINT_KINDS`, issue
//! 28) are those the importer reads.

use std::collections::BTreeSet;

use camlink_adm::CONSTRAINT_TYPES;
use camlink_model::JOINT_KINDS;

#[test]
fn course_types_map_onto_kinds() {
    let mapped: BTreeSet<&str> = JOINT_KINDS
        .iter()
        .flat_map(|k| k.course_types.iter().copied())
        .collect();
    let read: BTreeSet<&str> = CONSTRAINT_TYPES.iter().copied().collect();
    assert_eq!(
        mapped, read,
        "every course constraint type the importer reads names the kinds it becomes"
    );
}
