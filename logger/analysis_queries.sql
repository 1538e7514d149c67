-- Analysis queries in the style of the original's (they mix the case of
-- table names: pose / Pose, simulationRow / SimulationRow). They run
-- unchanged because the server has lower_case_table_names=1; the logger
-- tests run every one of them. Set @simulation to a Simulation.simulationID
-- first (simpartner-query list shows them), e.g.
--   mariadb --defaults-file=state/mariadb/reader.cnf simpartner \
--     -e "SET @simulation = 1; source logger/analysis_queries.sql"

-- 1. Trajectory of the front right wheel in the ground plane.
SELECT simulationRow.simulationTime, pose.x, pose.z
FROM pose, simulationRow, Body
WHERE pose.simulationRowID = simulationRow.simulationRowID
  AND Pose.bodyID = body.bodyID AND body.name = 'Wheel1'
  AND SimulationRow.simulationID = @simulation
ORDER BY simulationrow.simulationTime;

-- 2. Vertical contact force on each wheel over time.
SELECT SimulationRow.simulationTime, body.name, ForceAndTorque.F_y
FROM forceandtorque, SimulationRow, body
WHERE forceAndTorque.simulationRowID = simulationrow.simulationRowID
  AND ForceAndTorque.bodyID = Body.bodyID
  AND Body.name IN ('Wheel1', 'Wheel2', 'Wheel3', 'Wheel4')
  AND simulationRow.simulationID = @simulation
ORDER BY SimulationRow.simulationTime, body.name;

-- 3. Mean wheel load per wheel (the static wheel loads of the validation).
SELECT body.name, AVG(forceandtorque.F_y) AS meanLoad, COUNT(*) AS samples
FROM ForceAndTorque, simulationRow, Body
WHERE ForceAndTorque.simulationRowID = SimulationRow.simulationRowID
  AND forceandtorque.bodyID = body.bodyID
  AND body.name LIKE 'Wheel_'
  AND SIMULATIONROW.simulationID = @simulation
GROUP BY Body.name
ORDER BY Body.name;

-- 4. Steering angle of the Turner joint over time, found through the
--    robot's components.
SELECT simulationrow.simulationTime, jointpose.angle
FROM JointPose, SimulationRow, robotcomponent, Robot
WHERE jointPose.simulationRowID = simulationRow.simulationRowID
  AND RobotComponent.type = 'JOINT' AND robotComponent.name = 'Turner'
  AND RobotComponent.reference = JointPose.jointID
  AND robot.robotID = RobotComponent.robotID
  AND ROBOT.simulationID = @simulation
  AND simulationrow.simulationID = @simulation
ORDER BY SimulationRow.simulationTime;

-- 5. Height and tilt of the lower legs at the last logged step.
SELECT Body.name, pose.y, Pose.angle
FROM Pose, body, simulationRow
WHERE pose.bodyID = Body.bodyID AND body.name LIKE 'Calf%'
  AND Pose.simulationRowID = SimulationRow.simulationRowID
  AND simulationRow.simulationID = @simulation
  AND simulationrow.step = (SELECT MAX(step) FROM SIMULATIONROW WHERE simulationID = @simulation)
ORDER BY body.name;

-- 6. How far the Turner joint moved (extent of its anchor).
SELECT MIN(JointPose.anchorx), MAX(jointpose.anchorx), MIN(jointPose.anchorz), MAX(JOINTPOSE.anchorz)
FROM jointpose, RobotComponent, simulationRow
WHERE robotcomponent.type = 'JOINT' AND RobotComponent.name = 'Turner'
  AND robotComponent.reference = jointpose.jointID
  AND JointPose.simulationRowID = simulationrow.simulationRowID
  AND SimulationRow.simulationID = @simulation;

-- 7. Rows logged for the simulation, per table.
SELECT (SELECT COUNT(*) FROM simulationrow WHERE simulationID = @simulation) AS steps,
       (SELECT COUNT(*) FROM pose p, SimulationRow s
         WHERE p.simulationRowID = s.simulationRowID AND s.simulationID = @simulation) AS poses,
       (SELECT COUNT(*) FROM ForceAndTorque f, simulationRow s
         WHERE f.simulationRowID = s.simulationRowID AND s.simulationID = @simulation) AS forces,
       (SELECT COUNT(*) FROM jointPose j, SIMULATIONROW s
         WHERE j.simulationRowID = s.simulationRowID AND s.simulationID = @simulation) AS joints;

-- 8. Traction against slip of the front right wheel on soft soil, in the
--    steps it pressed the soil (docs/soil.md): the shear's traction
--    (thrust), the drawbar pull (thrust less compaction resistance), its
--    sinkage and load. Plot thrust / wheelLoad against slip.
SELECT WheelSoil.slip, wheelsoil.thrust, WheelSoil.drawbarPull, wheelSoil.sinkage, WheelSoil.wheelLoad
FROM wheelsoil, simulationRow, Body
WHERE WheelSoil.simulationRowID = SimulationRow.simulationRowID
  AND WheelSoil.bodyID = body.bodyID AND body.name = 'Wheel1'
  AND simulationrow.simulationID = @simulation
ORDER BY WheelSoil.slip;
