// The one table of sensor kinds (sensor_kinds.h): every sensor_t.KIND_*
// is in it once, and a reading's size is the layout sensor_reading_t.lcm
// documents.
#include <gtest/gtest.h>

#include <set>
#include <string>

#include "simpartner/sensor_kinds.h"

namespace simpartner {
namespace {

TEST(SensorKinds, EveryKindOnceInOrderWithItsNames) {
  const std::vector<SensorKindSpelling>& kinds = SensorKindSpellings();
  ASSERT_EQ(kinds.size(), 11u);  // KIND_ECHO (0) .. KIND_CAMERA (10)
  std::set<std::string> words, names;
  for (size_t k = 0; k < kinds.size(); ++k) {
    EXPECT_EQ(kinds[k].kind, static_cast<int>(k));
    EXPECT_TRUE(words.insert(kinds[k].word).second) << kinds[k].word;
    EXPECT_TRUE(names.insert(kinds[k].database).second) << kinds[k].database;
    EXPECT_LE(std::string(kinds[k].database).size(), 16u) << "Sensor.type is VARCHAR(16)";
  }
  EXPECT_STREQ(SpellSensorKind(sensor_t::KIND_FORCE_TORQUE).database, "FORCE_TORQUE");
  EXPECT_STREQ(SpellSensorKind(sensor_t::KIND_IMU).word, "imu");
  EXPECT_STREQ(SpellSensorKind(sensor_t::KIND_CAMERA).database, "CAMERA");
  EXPECT_STREQ(SpellSensorKind(42).database, "UNKNOWN");
}

sensor_t Sensor(int8_t kind, std::vector<double> params = {}) {
  sensor_t s{};
  s.kind = kind;
  s.params = std::move(params);
  s.num_params = static_cast<int32_t>(s.params.size());
  return s;
}

TEST(SensorKinds, AReadingHasTheValuesItsLayoutLists) {
  EXPECT_EQ(ReadingSize(Sensor(sensor_t::KIND_ECHO)), 0);  // text
  EXPECT_EQ(ReadingSize(Sensor(sensor_t::KIND_POSITION)), 7);
  EXPECT_EQ(ReadingSize(Sensor(sensor_t::KIND_VELOCITY)), 6);
  EXPECT_EQ(ReadingSize(Sensor(sensor_t::KIND_FORCE_TORQUE)), 6);
  EXPECT_EQ(ReadingSize(Sensor(sensor_t::KIND_SCANNER, {31, 0.5, 10})), 31);
  EXPECT_EQ(ReadingSize(Sensor(sensor_t::KIND_IMU)), 10);      // ax ay az wx wy wz qw qx qy qz
  EXPECT_EQ(ReadingSize(Sensor(sensor_t::KIND_GNSS)), 10);     // fix e n u ve vn vu lat lon alt
  EXPECT_EQ(ReadingSize(Sensor(sensor_t::KIND_ENCODER)), 2);   // count, rate
  // Lidar parameters: rays, halfSpan, layers, ...
  EXPECT_EQ(ReadingSize(Sensor(sensor_t::KIND_LIDAR, {360, 3.14, 4, -0.1, 0.1, 0, 50, 0, 0})), 1440);
  EXPECT_EQ(ReadingSize(Sensor(sensor_t::KIND_CONTACT)), 5);   // touching |F| fx fy fz
  EXPECT_EQ(ReadingSize(Sensor(sensor_t::KIND_CAMERA, {640, 480, 1.2, 0.1, 50, 2})), 0);
}

TEST(SensorKinds, EachValueHasTheNameOfItsLayout) {
  using Names = std::vector<std::string>;
  EXPECT_EQ(ReadingColumns(Sensor(sensor_t::KIND_IMU)),
            (Names{"ax", "ay", "az", "wx", "wy", "wz", "qw", "qx", "qy", "qz"}));
  EXPECT_EQ(ReadingColumns(Sensor(sensor_t::KIND_ENCODER)), (Names{"count", "count_rate"}));
  EXPECT_EQ(ReadingColumns(Sensor(sensor_t::KIND_CONTACT)),
            (Names{"touching", "force", "fx", "fy", "fz"}));
  EXPECT_EQ(ReadingColumns(Sensor(sensor_t::KIND_GNSS)).front(), "fix");
  EXPECT_EQ(ReadingColumns(Sensor(sensor_t::KIND_GNSS)).back(), "altitude");
  EXPECT_EQ(ReadingColumns(Sensor(sensor_t::KIND_SCANNER, {3, 0.1, 10})),
            (Names{"range_0", "range_1", "range_2"}));
  EXPECT_TRUE(ReadingColumns(Sensor(sensor_t::KIND_ECHO)).empty());
  EXPECT_TRUE(ReadingColumns(Sensor(sensor_t::KIND_CAMERA, {640, 480, 1.2, 0.1, 50, 2})).empty());
}

TEST(SensorKinds, ALidarReadingIsLayersByRays) {
  const sensor_t lidar = Sensor(sensor_t::KIND_LIDAR, {360, 3.14, 4, -0.1, 0.1, 0, 50, 0, 0});
  EXPECT_EQ(ShapeOfReading(lidar).rows, 4);
  EXPECT_EQ(ShapeOfReading(lidar).columns, 360);
  EXPECT_EQ(ReadingColumns(lidar).size(), 360u);
  EXPECT_EQ(ReadingColumns(lidar)[359], "range_359");
  const sensor_t scanner = Sensor(sensor_t::KIND_SCANNER, {11, 0.1, 10});
  EXPECT_EQ(ShapeOfReading(scanner).rows, 1);
  EXPECT_EQ(ShapeOfReading(scanner).columns, 11);
  EXPECT_EQ(ShapeOfReading(Sensor(sensor_t::KIND_IMU)).columns, 10);
}

}  // namespace
}  // namespace simpartner
